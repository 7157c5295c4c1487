// `glrefcheck digest` alone, for the build checks of the reference's bits (tests/CMakeLists.txt):
//   glrc_digest PATH...                       the frames' digests (tests/digests.txt), also
//                                              linked against flag variants of the reference
//                                              (-O0, -O3 -march=native -ffp-contract=fast);
//   glrc_digest --expectation BITS PATH...    ref::expectation_digest with the allowance of
//                                              BITS subpixel bits: every bit render() gives
//                                              (tests/expectation_digests.txt);
//   glrc_digest --threads N ...               either, drawn on N threads (default 1).
#include <cstdio>
#include <exception>
#include <optional>
#include <string>

#include "casefile/casefile.hpp"
#include "ref/reference.hpp"

int main(int argc, char** argv) {
  try {
    std::vector<std::string> paths(argv + 1, argv + argc);
    std::optional<int> bits;
    int threads = 1;
    while (paths.size() >= 2 && (paths[0] == "--expectation" || paths[0] == "--threads")) {
      if (paths[0] == "--threads")
        threads = std::stoi(paths[1]);
      else
        bits = std::stoi(paths[1]);
      paths.erase(paths.begin(), paths.begin() + 2);
    }
    for (const auto& file : glrc::casefile::collect(paths)) {
      const glrc::Case c = glrc::casefile::load(file);
      const glrc::Expectation r = glrc::ref::render(c, glrc::Model{}, bits, threads);
      const std::string d = bits ? glrc::ref::expectation_digest(r) : glrc::ref::digest(r.frame);
      std::printf("%s  %s\n", d.c_str(), c.name.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
