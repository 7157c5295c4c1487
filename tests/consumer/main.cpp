// glrefcheck as a library: load a case, render the exact reference, and compare frames with it.
// The reference against itself must pass; a copy with one value changed must fail.
//   consumer CASE.json
#include <cstddef>
#include <cstdio>
#include <exception>
#include <vector>

#include "casefile/casefile.hpp"
#include "check/check.hpp"
#include "compare/compare.hpp"
#include "ref/reference.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer CASE.json\n");
    return 2;
  }
  try {
    const glrc::Case c = glrc::casefile::load(argv[1]);
    // Judged as `run` judges an implementation that reports 8 subpixel bits: the specification's
    // allowance around the exact reference, the case's tolerance.
    const glrc::check::CheckOptions options;
    const int reported_bits = 8;
    const glrc::Expectation reference =
        glrc::ref::render(c, options.model, glrc::check::freedom_bits(options, reported_bits));
    const glrc::Tolerance tolerance = glrc::check::tolerance_for(c, options, reported_bits);

    const glrc::CaseResult same = glrc::compare::compare(c, reference, reference.frame, tolerance);

    // One value changed by far more than any allowance: the first component at the middle one of
    // the covered pixels (colours are in [0, 1], so 0.25 is millions of ULPs).
    glrc::Frame changed = reference.frame;
    std::vector<size_t> covered;
    for (size_t i = 0; i < changed.primitive.size(); ++i)
      if (changed.primitive[i] != glrc::Frame::kNoPrimitive) covered.push_back(i);
    if (covered.empty() || changed.components.empty()) {
      std::fprintf(stderr, "%s: no covered pixel with a varying to change\n", c.name.c_str());
      return 1;
    }
    const size_t pixel = covered[covered.size() / 2];
    changed.components[0][pixel] += 0.25f;
    const glrc::CaseResult differs = glrc::compare::compare(c, reference, changed, tolerance);

    std::printf("%s: %zu covered pixels, reference digest %s\n", c.name.c_str(), covered.size(),
                glrc::ref::digest(reference.frame).c_str());
    std::printf("reference against itself: %s\n", glrc::to_string(same.status));
    std::printf("one value changed at (%zu, %zu): %s%s%s\n", pixel % size_t(changed.width),
                pixel / size_t(changed.width), glrc::to_string(differs.status),
                differs.message.empty() ? "" : ": ", differs.message.c_str());
    return same.status == glrc::Status::pass && differs.status == glrc::Status::fail ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
