// The C reproducer's coverage verdict against the comparator's, without GL: every combination
// of what the reference expects at a pixel (its primitive, fragment count and edge bits), what
// GL did there (the reference's primitive, a candidate of the depth test, another, none; fewer,
// as many or more fragments; a trace admitted, not admitted or not listed) and how the case is
// judged (with and without fragment counts, coverage differences at edges allowed or not) is
// judged by compare::compare on a one-pixel frame and by export/c_runtime/verdict.c, compiled
// alone with -std=c99 -Wall -Wextra -pedantic -Werror, with the verdict table c_verdict_table
// writes. They must give the same label and the same pass or fail everywhere.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "compare/compare.hpp"
#include "core/fragment_trace.hpp"
#include "export/c_runtime.hpp"
#include "export/coverage_verdict_table.hpp"
#include "export/reproducer.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

using namespace glrc;

enum class TraceKind { unlisted, admitted, not_admitted };

// One pixel's inputs.
struct Scenario {
  int32_t reference = 0;  // -1: the reference covers nothing
  uint16_t reference_fragments = 1;
  uint8_t edges = 0;
  int32_t gl = 0;  // GL's kept primitive: 0 the reference's, 1 the candidate, 2 another, -1 none
  uint16_t gl_fragments = 1;
  TraceKind trace = TraceKind::unlisted;
};

// GL's trace at the pixel: gl_fragments fragments of its kept primitive (of primitive 0 where
// it keeps none).
FragmentTrace gl_trace(const Scenario& s) {
  FragmentTrace t;
  for (int k = 0; k < s.gl_fragments; ++k)
    t += fragment_trace(s.gl < 0 ? 0 : s.gl);
  return t;
}

// What a conforming implementation may give there, as the scenario says: GL's trace, another
// (one more fragment), or nothing decided.
FragmentChoices choices_of(const Scenario& s) {
  FragmentChoices c;
  if (s.trace == TraceKind::unlisted) {
    c.anything = true;
    return c;
  }
  c.sure = gl_trace(s);
  if (s.trace == TraceKind::not_admitted) c.sure += fragment_trace(0);
  return c;
}

std::vector<Scenario> every_scenario() {
  std::vector<Scenario> all;
  const std::pair<int32_t, uint16_t> references[] = {{0, 1}, {0, 2}, {-1, 0}};
  for (const auto& [reference, fragments] : references)
    for (int edges = 0; edges < reproducer::CoverageVerdictTable::kEdgeBitValues; ++edges)
      for (int32_t gl : {0, 1, 2, -1})
        for (int delta : {-1, 0, 1})
          for (TraceKind trace :
               {TraceKind::unlisted, TraceKind::admitted, TraceKind::not_admitted}) {
            if (fragments + delta < 0) continue;
            all.push_back(
                {reference, fragments, uint8_t(edges), gl, uint16_t(fragments + delta), trace});
          }
  return all;
}

// A case of three triangles (primitives 0, 1 and 2) and no varyings over one pixel.
Case one_pixel_case() {
  Case c;
  c.name = "parity";
  c.fb_width = c.fb_height = 1;
  c.viewport = {0, 0, 1, 1};
  for (int v = 0; v < 3; ++v)
    c.vertices.push_back({{float(v), 0, 0, 1}, {}});
  c.triangles = {{0, 1, 2}, {0, 1, 2}, {0, 1, 2}};
  return c;
}

// The comparator's label code (label_code) and whether the pixel fails, for one scenario.
std::pair<int, bool> comparator_verdict(const Case& c, const Scenario& s, bool counts,
                                        const Tolerance& tolerance) {
  Expectation e;
  e.frame = Frame(1, 1, 0);
  e.frame.primitive[0] = s.reference;
  e.frame.depth[0] = 0.5f;
  e.edges = {s.edges};
  e.allowed = Frame(1, 1, 0);
  e.allowed.depth[0] = 0.0f;
  Candidate candidate;
  candidate.pixel = 0, candidate.primitive = 1, candidate.depth = 0.5f;
  e.candidates = {candidate};
  Frame gl(1, 1, 0);
  gl.primitive[0] = s.gl;
  gl.depth[0] = 0.5f;
  if (counts) {
    e.frame.fragments = {s.reference_fragments};
    gl.fragments = {s.gl_fragments};
  }
  compare::TraceSource traces;
  traces.gl = [&](const std::vector<size_t>& pixels) {
    return std::vector<std::optional<FragmentTrace>>(pixels.size(), gl_trace(s));
  };
  traces.choices = [&](const std::vector<size_t>& pixels) {
    return std::vector<FragmentChoices>(pixels.size(), choices_of(s));
  };
  const CaseResult r = compare::compare(c, e, gl, tolerance, 1, &traces);
  const CoverageStats& cov = r.coverage;
  using Label = CoverageStats::Label;
  std::optional<Label> label;
  const std::pair<uint64_t, Label> counters[] = {{cov.exact_tie, Label::exact_tie},
                                                 {cov.within_snapping, Label::within_snapping},
                                                 {cov.gaps, Label::gap},
                                                 {cov.double_hits, Label::double_hit},
                                                 {cov.fill_rule, Label::fill_rule}};
  for (const auto& [n, l] : counters) {
    EXPECT_LE(n, 1u);
    if (n) label = l;
  }
  return {reproducer::label_code(label), cov.failures > 0};
}

// A C program that judges every scenario with verdict.c and prints "label fails" per line.
std::string c_program(const std::vector<Scenario>& all, bool counts,
                      const reproducer::CoverageVerdictTable& table) {
  std::ostringstream out;
  out << "#include <math.h>\n#include <stddef.h>\n#include <stdio.h>\n#define CHANNELS 1\n";
  out << reproducer::kCVerdict << reproducer::c_verdict_table(table);
  out << "struct scenario {\n  struct expected_coverage expected;\n  int gl_primitive;\n"
         "  unsigned gl_fragments;\n  float trace[2];\n  int listed;\n  unsigned "
         "admitted[3];\n};\n";
  out << "static const struct scenario SCENARIOS[] = {\n";
  for (const Scenario& s : all) {
    const FragmentTrace t = gl_trace(s);
    const std::optional<std::vector<FragmentTrace>> listed = admitted(choices_of(s));
    const FragmentTrace a = listed && !listed->empty() ? listed->front() : FragmentTrace{};
    out << "    {{" << s.reference << ", " << s.reference_fragments << ", " << int(s.edges) << "}, "
        << s.gl << ", " << s.gl_fragments << ", {" << t.id_sum << ".0f, " << t.hash_sum << ".0f}, "
        << int(listed.has_value()) << ", {" << a.count << ", " << a.id_sum << ", " << a.hash_sum
        << "}},\n";
  }
  out << "};\n";
  out << "int main(void) {\n"
         "  size_t n;\n"
         "  for (n = 0; n < sizeof SCENARIOS / sizeof SCENARIOS[0]; ++n) {\n"
         "    const struct scenario *s = &SCENARIOS[n];\n"
         "    const struct candidate candidates[1] = {{0, 1, {0.5f}, {0.0}}};\n"
         "    const struct traced pixel = {0, 0, 1};\n"
         "    const struct trace_list traces = {s->listed, &pixel, &s->admitted};\n"
         "    const struct candidate *other =\n"
         "        s->gl_primitive != s->expected.primitive\n"
         "            ? candidate_of(candidates, candidates + 1, s->gl_primitive) : NULL;\n"
         "    const enum label label = pixel_label(COVERAGE_VERDICT, "
      << int(counts)
      << ", &traces, 0, &s->expected,\n"
         "                                         s->gl_primitive, s->gl_fragments, s->trace, "
         "other);\n"
         "    printf(\"%d %d\\n\", (int)label, (int)LABEL_FAILS[label]);\n"
         "  }\n"
         "  return 0;\n"
         "}\n";
  return out.str();
}

class CVerdictParity : public glrc::test::TempDirTest {};

TEST_F(CVerdictParity, EveryCoverageInputIsJudgedAsTheComparatorJudgesIt) {
  const Case c = one_pixel_case();
  const std::vector<Scenario> all = every_scenario();
  int judged = 0, failing = 0;
  for (bool counts : {false, true})
    for (bool allow_boundary : {false, true}) {
      Tolerance tolerance;
      tolerance.mode = ToleranceMode::spec;
      tolerance.allow_boundary = allow_boundary;
      const reproducer::CoverageVerdictTable table(counts, tolerance);
      const std::string name = "parity_" + std::to_string(counts) + std::to_string(allow_boundary);
      const std::string source = (dir_ / (name + ".c")).string();
      const std::string program = (dir_ / name).string();
      std::ofstream(source) << c_program(all, counts, table);
      const std::string compile = "cc -std=c99 -O1 -Wall -Wextra -pedantic -Werror -o '" + program +
                                  "' '" + source + "' -lm 2>&1";
      ASSERT_EQ(std::system(compile.c_str()), 0) << compile;
      FILE* p = popen(("'" + program + "'").c_str(), "r");
      ASSERT_NE(p, nullptr);
      for (const Scenario& s : all) {
        int label = -1, fails = -1;
        ASSERT_EQ(std::fscanf(p, "%d %d", &label, &fails), 2);
        const auto [expected_label, expected_fails] = comparator_verdict(c, s, counts, tolerance);
        EXPECT_EQ(label, expected_label)
            << "counts " << counts << ", allow_boundary " << allow_boundary << ", reference "
            << s.reference << " x" << s.reference_fragments << ", edges " << int(s.edges) << ", GL "
            << s.gl << " x" << s.gl_fragments << ", trace " << int(s.trace);
        EXPECT_EQ(fails != 0, expected_fails)
            << "counts " << counts << ", allow_boundary " << allow_boundary << ", edges "
            << int(s.edges) << ", GL " << s.gl << " x" << s.gl_fragments;
        ++judged;
        failing += expected_fails;
      }
      EXPECT_EQ(pclose(p), 0);
    }
  // Both sides of every rule were reached: passes and failures, every label.
  EXPECT_EQ(judged, 4 * int(all.size()));
  EXPECT_GT(failing, judged / 10);
  EXPECT_LT(failing, judged - judged / 10);
}

}  // namespace
