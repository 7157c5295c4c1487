// The digest command alone, linked against a flag variant of the reference (-O0, or -O3
// -march=native -ffp-contract=fast), to show that flags do not change a single reference bit.
#include <cstdio>
#include <exception>

#include "casefile/casefile.hpp"
#include "ref/reference.hpp"

int main(int argc, char** argv) {
  try {
    std::vector<std::string> paths(argv + 1, argv + argc);
    for (const auto& file : glrc::casefile::collect(paths)) {
      const glrc::Case c = glrc::casefile::load(file);
      std::printf("%s  %s\n", glrc::ref::digest(glrc::ref::render(c, glrc::Model{}).frame).c_str(),
                  c.name.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
