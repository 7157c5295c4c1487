// Random campaigns without GL: the generators' determinism and validity, failure classes,
// shrinking on a planted fault (a renderer that draws the exact reference and plants NaN where
// a triangle has a vertex with w_c < 1), and a whole campaign on that fault.
#include <gtest/gtest.h>

#include <gmpxx.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "campaign/campaign.hpp"
#include "campaign/failure.hpp"
#include "campaign/generators.hpp"
#include "campaign/random.hpp"
#include "campaign/shrink.hpp"
#include "casefile/casefile.hpp"
#include "casefile/write.hpp"
#include "check/check.hpp"

namespace {

using namespace glrc;
using namespace glrc::campaign;

std::vector<const Generator*> all_generators() {
  std::vector<const Generator*> out;
  for (const Generator& g : generators())
    out.push_back(&g);
  return out;
}

std::vector<const Generator*> only(std::string_view name) {
  const Generator* g = find_generator(name);
  EXPECT_NE(g, nullptr) << name;
  return {g};
}

TEST(Random, IsSplitMix64) {
  // The first outputs of SplitMix64 seeded with 42, from an independent implementation.
  Random r(42);
  EXPECT_EQ(r.next(), 13679457532755275413ull);
  EXPECT_EQ(r.next(), 2949826092126892291ull);
  EXPECT_EQ(r.next(), 5139283748462763858ull);
  Random again(42);
  EXPECT_EQ(again.below(1000), 741u);  // the high 64 bits of 13679457532755275413 * 1000
  for (int k = 0; k < 1000; ++k) {
    const int v = again.between(-3, 3);
    EXPECT_GE(v, -3);
    EXPECT_LE(v, 3);
    const double b = again.binades(-2, 1);
    EXPECT_GE(b, 0.25);
    EXPECT_LT(b, 4.0);
  }
}

TEST(Generators, EveryNameIsFoundAndNothingElse) {
  EXPECT_EQ(generators().size(), 10u);
  for (const char* name : {"sizes", "clip", "mesh", "attributes", "states", "dense", "assembly",
                           "window", "distances", "depth"})
    EXPECT_NE(find_generator(name), nullptr) << name;
  EXPECT_EQ(find_generator("Clip"), nullptr);
  EXPECT_EQ(find_generator(""), nullptr);
}

TEST(Generators, TheSameSeedAndIndexGiveTheSameCaseAndEveryCaseLoads) {
  const auto chosen = all_generators();
  std::set<std::string> texts;
  for (uint64_t index = 0; index < 150; ++index) {
    const Case a = generate(chosen, 7, index);
    const Case b = generate(chosen, 7, index);
    const std::string text = casefile::to_case_file(a);
    ASSERT_EQ(text, casefile::to_case_file(b)) << a.name;
    texts.insert(text);
    EXPECT_EQ(a.name, "fuzz_" + std::string(generator_for(chosen, index).name) + "_7_" +
                          std::to_string(index));
    EXPECT_FALSE(a.triangles.empty()) << a.name;
    // The loader takes it as it is: the same bits back.
    Case loaded;
    ASSERT_NO_THROW(loaded = casefile::parse(text, a.name, a.name)) << text.substr(0, 400);
    EXPECT_EQ(casefile::to_case_file(loaded), text) << a.name;
    // A generator's case does not depend on which others the campaign has.
    const Case alone = generate({&generator_for(chosen, index)}, 7, index);
    EXPECT_EQ(casefile::to_case_file(alone), text) << a.name;
  }
  EXPECT_EQ(texts.size(), 150u) << "two indices gave the same case";
  EXPECT_NE(casefile::to_case_file(generate(chosen, 8, 0)),
            casefile::to_case_file(generate(chosen, 7, 0)));
}

TEST(Generators, AimWhereTheySay) {
  // Over 60 cases each: clip puts vertices on the planes and behind the eye; mesh shares
  // vertices between triangles; attributes spans 1e-30 to 1e30; sizes makes long framebuffers.
  int on_plane = 0, behind = 0, shared = 0, tiny = 0, huge = 0, long_framebuffer = 0;
  for (uint64_t index = 0; index < 60; ++index) {
    const Case clip = generate(only("clip"), 3, index);
    for (const Vertex& v : clip.vertices) {
      on_plane += std::fabs(v.clip[0]) == std::fabs(v.clip[3]) && v.clip[3] != 0;
      behind += v.clip[3] <= 0;
    }
    const Case mesh = generate(only("mesh"), 3, index);
    shared += mesh.vertices.size() < 3 * mesh.triangles.size();
    const Case attributes = generate(only("attributes"), 3, index);
    for (const Vertex& v : attributes.vertices)
      for (const float x : v.values) {
        tiny += x != 0 && std::fabs(x) < 1e-25f;
        huge += std::fabs(x) > 1e25f;
      }
    const Case sizes = generate(only("sizes"), 3, index);
    long_framebuffer += std::max(sizes.fb_width, sizes.fb_height) >= 1024;
  }
  EXPECT_GT(on_plane, 20);
  EXPECT_GT(behind, 20);
  EXPECT_EQ(shared, 60);
  EXPECT_GT(tiny, 10);
  EXPECT_GT(huge, 10);
  EXPECT_GT(long_framebuffer, 3);
}

// The dense generator's scenes, looked at the way issue 44's false failures need them.
using ClipTriangle = std::array<std::array<float, 4>, 3>;

ClipTriangle clip_of(const Case& c, size_t t) {
  ClipTriangle out;
  for (size_t k = 0; k < 3; ++k)
    out[k] = c.vertices[c.triangles[t][k]].clip;
  return out;
}

bool inside_clip_volume(const std::array<float, 4>& p) {
  return p[3] > 0 && std::fabs(p[0]) < p[3] && std::fabs(p[1]) < p[3] && std::fabs(p[2]) < p[3];
}
bool unclipped(const ClipTriangle& t) {
  return std::all_of(t.begin(), t.end(), inside_clip_volume);
}

// A point inside the clip volume in window coordinates: x_w, y_w and z_n.
using WindowPoint = std::array<double, 3>;
using WindowTriangle = std::array<WindowPoint, 3>;
WindowPoint in_window(const Case& c, const std::array<float, 4>& p) {
  const double w = p[3];
  return {c.viewport.x + (p[0] / w + 1) * c.viewport.width / 2,
          c.viewport.y + (p[1] / w + 1) * c.viewport.height / 2, p[2] / w};
}
WindowTriangle in_window(const Case& c, const ClipTriangle& t) {
  return {in_window(c, t[0]), in_window(c, t[1]), in_window(c, t[2])};
}

// z_n at window point (x, y) when the point is strictly inside the window triangle.
std::optional<double> depth_inside(const WindowTriangle& t, double x, double y) {
  auto edge = [&](size_t a, size_t b, double px, double py) {
    return (t[b][0] - t[a][0]) * (py - t[a][1]) - (t[b][1] - t[a][1]) * (px - t[a][0]);
  };
  const double area = edge(0, 1, t[2][0], t[2][1]);
  if (std::fabs(area) < 0.5) return std::nullopt;  // thin: its pixels are no evidence here
  const double l0 = edge(1, 2, x, y) / area, l1 = edge(2, 0, x, y) / area;
  const double l2 = edge(0, 1, x, y) / area;
  if (l0 <= 0 || l1 <= 0 || l2 <= 0) return std::nullopt;
  return l0 * t[0][2] + l1 * t[1][2] + l2 * t[2][2];
}

// Whether the four clip positions lie in one hyperplane through the origin of clip space, so
// that their points share one depth plane: the exact 4x4 determinant (a float is a rational).
bool linearly_dependent(const std::array<std::array<float, 4>, 4>& rows) {
  std::array<std::array<mpq_class, 4>, 4> m;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      m[i][j] = mpq_class(double(rows[i][j]));
  for (size_t col = 0; col < 4; ++col) {
    size_t pivot = col;
    while (pivot < 4 && m[pivot][col] == 0)
      ++pivot;
    if (pivot == 4) return true;
    std::swap(m[pivot], m[col]);
    for (size_t i = col + 1; i < 4; ++i) {
      const mpq_class f = m[i][col] / m[col][col];
      for (size_t j = col; j < 4; ++j)
        m[i][j] -= f * m[col][j];
    }
  }
  return false;
}

// The same determinant in doubles, relative to the product of the rows' lengths (Hadamard's
// bound on it): rounding leaves about 1e-16 of dependent rows, the near-coplanar pairs' are
// about 1e-7, so above 1e-9 rules dependence out without rationals.
double relative_determinant(const std::array<std::array<float, 4>, 4>& rows) {
  auto at = [&](size_t i, size_t j) { return double(rows[i][j]); };
  // Laplace along the first row.
  auto minor = [&](size_t skip) {
    std::array<size_t, 3> k{};
    for (size_t j = 0, n = 0; j < 4; ++j)
      if (j != skip) k[n++] = j;
    return at(1, k[0]) * (at(2, k[1]) * at(3, k[2]) - at(2, k[2]) * at(3, k[1])) -
           at(1, k[1]) * (at(2, k[0]) * at(3, k[2]) - at(2, k[2]) * at(3, k[0])) +
           at(1, k[2]) * (at(2, k[0]) * at(3, k[1]) - at(2, k[1]) * at(3, k[0]));
  };
  double det = 0, bound = 1;
  for (size_t j = 0; j < 4; ++j)
    det += (j % 2 ? -1 : 1) * at(0, j) * minor(j);
  for (size_t i = 0; i < 4; ++i)
    bound *= std::hypot(std::hypot(at(i, 0), at(i, 1)), std::hypot(at(i, 2), at(i, 3)));
  return bound > 0 ? std::fabs(det) / bound : 0;
}

// Both triangles in one depth plane, exactly: each vertex of b on a's plane.
bool exactly_coplanar(const ClipTriangle& a, const ClipTriangle& b) {
  for (const auto& p : b) {
    const std::array<std::array<float, 4>, 4> rows{a[0], a[1], a[2], p};
    if (relative_determinant(rows) > 1e-9 || !linearly_dependent(rows)) return false;
  }
  return true;
}

// A pixel centre inside a, b and c (window triangles) where c is nearer than a by more than
// 1e-3 in z_n: a contest of a and b hidden under c.
bool hidden_under(const Case& cs, const WindowTriangle& a, const WindowTriangle& b,
                  const WindowTriangle& c) {
  // The intersection of their bounding boxes and the framebuffer.
  double x0 = 0, x1 = cs.fb_width, y0 = 0, y1 = cs.fb_height;
  for (const WindowTriangle* t : {&a, &b, &c}) {
    const auto [left, right] = std::minmax({(*t)[0][0], (*t)[1][0], (*t)[2][0]});
    const auto [bottom, top] = std::minmax({(*t)[0][1], (*t)[1][1], (*t)[2][1]});
    x0 = std::max(x0, left), x1 = std::min(x1, right);
    y0 = std::max(y0, bottom), y1 = std::min(y1, top);
  }
  if (x0 >= x1 || y0 >= y1) return false;
  // At most 64 x 64 pixel centres, evenly spread over the boxes' intersection.
  const double step_x = std::max(1.0, std::ceil((x1 - x0) / 64));
  const double step_y = std::max(1.0, std::ceil((y1 - y0) / 64));
  for (double y = std::floor(y0) + 0.5; y < y1; y += step_y)
    for (double x = std::floor(x0) + 0.5; x < x1; x += step_x) {
      const auto za = depth_inside(a, x, y), zb = depth_inside(b, x, y);
      const auto zc = depth_inside(c, x, y);
      if (za && zb && zc && *zc < *za - 1e-3) return true;
    }
  return false;
}

TEST(Generators, DenseScenesHideDepthContestsUnderNearerTriangles) {
  const auto dense = only("dense");
  int hidden_contests = 0, copies = 0;
  std::set<std::string> shared_edge_sizes;
  const int samples = 12;
  for (uint64_t seed = 1; seed <= 3; ++seed)
    for (uint64_t index = 0; index < uint64_t(samples / 3); ++index) {
      const Case c = generate(dense, seed, index);
      SCOPED_TRACE(c.name);
      EXPECT_EQ(c.depth_func, DepthFunc::less);
      EXPECT_GE(c.triangles.size(), 100u);
      EXPECT_LE(c.triangles.size(), 800u);
      EXPECT_GE(std::min(c.fb_width, c.fb_height), 64);
      EXPECT_LE(std::max(c.fb_width, c.fb_height), 512);
      // A case file the loader takes as it is.
      const std::string text = casefile::to_case_file(c);
      Case loaded;
      ASSERT_NO_THROW(loaded = casefile::parse(text, c.name, c.name)) << text.substr(0, 400);
      EXPECT_EQ(casefile::to_case_file(loaded), text);

      std::vector<ClipTriangle> clip;
      int clipped = 0;
      for (size_t t = 0; t < c.triangles.size(); ++t) {
        clip.push_back(clip_of(c, t));
        clipped += !unclipped(clip.back());
      }
      EXPECT_GT(clipped, 0);
      EXPECT_LT(clipped, int(clip.size()));

      // A bitwise-identical copy of an earlier triangle, in the same order, with other values.
      bool copy = false;
      for (size_t j = 0; j < clip.size() && !copy; ++j)
        for (size_t i = 0; i < j && !copy; ++i)
          copy = std::memcmp(&clip[i], &clip[j], sizeof(ClipTriangle)) == 0 &&
                 c.triangles[i] != c.triangles[j] &&
                 c.vertices[c.triangles[i][0]].values != c.vertices[c.triangles[j][0]].values;
      copies += copy;

      // Two different triangles in one exact depth plane, overlapping, and a later nearer one
      // over both: issue 44's smallest false failure.
      bool hidden = false;
      for (size_t j = 0; j < clip.size() && !hidden; ++j) {
        if (!unclipped(clip[j])) continue;
        const auto wj = in_window(c, clip[j]);
        for (size_t i = 0; i < j && !hidden; ++i) {
          if (!unclipped(clip[i]) || std::memcmp(&clip[i], &clip[j], sizeof(ClipTriangle)) == 0 ||
              !exactly_coplanar(clip[i], clip[j]))
            continue;
          const auto wi = in_window(c, clip[i]);
          for (size_t k = j + 1; k < clip.size() && !hidden; ++k)
            hidden = unclipped(clip[k]) && hidden_under(c, wi, wj, in_window(c, clip[k]));
        }
      }
      hidden_contests += hidden;

      // Edges two triangles share by vertex index, by their length in the window.
      std::map<std::pair<uint32_t, uint32_t>, int> edges;
      for (const auto& t : c.triangles)
        for (size_t k = 0; k < 3; ++k)
          ++edges[std::minmax(t[k], t[(k + 1) % 3])];
      for (const auto& [edge, users] : edges) {
        const auto& p = c.vertices[edge.first].clip;
        const auto& q = c.vertices[edge.second].clip;
        if (users < 2 || !inside_clip_volume(p) || !inside_clip_volume(q)) continue;
        const WindowPoint from = in_window(c, p), to = in_window(c, q);
        const double length = std::hypot(to[0] - from[0], to[1] - from[1]);
        if (length < 1) shared_edge_sizes.insert("tiny");
        if (length >= 1 && length < 4) shared_edge_sizes.insert("small");
        if (length >= 16 && length <= 64) shared_edge_sizes.insert("medium");
        if (length > 64) shared_edge_sizes.insert("large");
      }
    }
  EXPECT_GE(hidden_contests, samples / 2);
  EXPECT_GE(copies, samples / 2);
  EXPECT_EQ(shared_edge_sizes, (std::set<std::string>{"tiny", "small", "medium", "large"}));
}

// Issue 45: under --strict-coverage, 38 within-snapping pixels were filed as value/other.
TEST(Failures, StrictCoverageBoundaryMismatchesAreTheirOwnClass) {
  Case c;
  CaseResult r;
  r.outcome = Status::fail;
  r.tolerance.allow_boundary = false;
  r.coverage.within_snapping = 38, r.coverage.exact_tie = 2;
  r.coverage.boundary = r.coverage.failures = 40;
  const std::vector<Failure> f = failures_of(c, r);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[0].signature(), "boundary/within_snapping");
  EXPECT_EQ(f[1].signature(), "boundary/exact_tie");
  EXPECT_EQ(failure_file_name(f[0]), "boundary_within_snapping.json");
  // With the boundary allowed, those pixels fail nothing: no boundary class (the outcome is
  // forced here; a real check would pass).
  r.tolerance.allow_boundary = true;
  EXPECT_EQ(failures_of(c, r).front().signature(), "value/other");
}

TEST(Failures, ClassesComeInPrecedenceOrderWithTheChannelsKind) {
  Case c;
  c.varyings = {{"a", 2, Interpolation::noperspective}, {"b", 1, Interpolation::flat}};
  CaseResult r;
  r.outcome = Status::fail;
  r.channels.resize(4);
  r.channels[0].name = "depth";
  r.channels[1].name = "a.x";
  r.channels[2].name = "a.y";
  r.channels[3].name = "b";
  r.channels[2].non_finite = 3, r.channels[2].over_tolerance = 5;
  r.channels[0].over_tolerance = 1;
  r.coverage.gaps = 2;
  const std::vector<Failure> f = failures_of(c, r);
  ASSERT_EQ(f.size(), 4u);
  EXPECT_EQ(f[0].signature(), "non_finite/noperspective");
  EXPECT_EQ(f[1].signature(), "gap");
  EXPECT_EQ(f[2].signature(), "value/depth");
  EXPECT_EQ(f[3].signature(), "value/noperspective");
  r.outcome = Status::crash;
  EXPECT_EQ(failures_of(c, r).front().signature(), "crash");
  r.outcome = Status::skip;  // beyond GL's specified range: not judged
  EXPECT_TRUE(failures_of(c, r).empty());
  r.outcome = Status::pass;
  EXPECT_TRUE(failures_of(c, r).empty());
  EXPECT_EQ(failure_file_name(f[0]), "non_finite_noperspective.json");
}

// The third hostile campaign (issue 45): a value failure's description gave a NaN pixel, and
// counted the NaN pixels (the non_finite failure's) among its own.
TEST(Failures, AValueFailureIsDescribedByItsFinitePixels) {
  Case c;
  c.varyings = {{"v0", 2, Interpolation::noperspective}};
  CaseResult r;
  r.outcome = Status::fail;
  r.channels.resize(1);
  ChannelStats& ch = r.channels[0];
  ch.name = "v0.x";
  ch.compared = 100, ch.non_finite = 3, ch.over_tolerance = 5;
  ch.worst = {{4, 5, 0.5f, NAN, INFINITY, INFINITY, 0.1, INFINITY},
              {6, 7, 0.5f, 0.75f, 0.25, 10, 0.125, 2}};
  const std::vector<Failure> f = failures_of(c, r);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(describe(f[0], r),
            "non_finite/noperspective: v0.x at (4, 5): GL nan, reference 0.5, 3 pixels");
  EXPECT_EQ(describe(f[1], r),
            "value/noperspective: v0.x at (6, 7): GL 0.75, reference 0.5, 2x the allowance, 2 "
            "pixels");
  // Its worst pixels kept all NaN: the count alone.
  ch.worst.pop_back();
  EXPECT_EQ(describe(f[1], r), "value/noperspective: v0.x, 2 pixels");
}

TEST(Shrink, SimplerNumbersComeFirst) {
  EXPECT_EQ(complexity(0.0f), 0);
  EXPECT_LT(complexity(0.0f), complexity(-0.0f));
  EXPECT_LT(complexity(-0.0f), complexity(1.0f));
  EXPECT_LT(complexity(1.0f), complexity(-1.0f));
  EXPECT_LT(complexity(1.0f), complexity(3.0f));
  EXPECT_LT(complexity(3.0f), complexity(0.5f));   // integers before fractions
  EXPECT_LT(complexity(0.5f), complexity(0.75f));  // fewer mantissa bits
  EXPECT_LT(complexity(0.75f), complexity(0.1f));
  EXPECT_LT(complexity(16.0f), complexity(17.0f));
  EXPECT_LT(complexity(0x1p-3f), complexity(0x1p-60f));  // smaller exponents
}

// "GL": the exact reference's own frame, with NaN planted in the first component wherever the
// covering triangle has a vertex with 0 < w_c < 1 and that component is smooth.
class PlantedFault : public gl::Renderer {
 public:
  PlantedFault() { info_.renderer = "planted fault (test)", info_.subpixel_bits = 8; }
  const gl::GlInfo& info() const override { return info_; }
  Frame render(const Case& c) override {
    Frame f = check::expectation_for(c, check::CheckOptions{}, 8).frame;
    if (c.varyings.empty() || c.varyings[0].interpolation != Interpolation::smooth) return f;
    for (size_t p = 0; p < f.pixel_count(); ++p) {
      const int32_t t = f.primitive[p];
      if (t < 0) continue;
      bool near = false;
      for (const uint32_t v : c.triangles[size_t(t)])
        near = near || (c.vertices[v].clip[3] > 0 && c.vertices[v].clip[3] < 1);
      if (near) f.components[0][p] = NAN;
    }
    return f;
  }

 private:
  gl::GlInfo info_;
};

Judge planted_judge(int* checks = nullptr) {
  return [checks](const std::vector<Case>& cases) {
    PlantedFault gl;
    std::vector<CaseResult> out;
    for (const Case& c : cases)
      out.push_back(check::check(c, gl, check::CheckOptions{}));
    if (checks) *checks += int(cases.size());
    return out;
  };
}

// The first case of the states generator (seed 11) that the planted fault fails.
std::pair<Case, CaseResult> first_planted_failure() {
  const Judge judge = planted_judge();
  for (uint64_t index = 0; index < 200; ++index) {
    Case c = generate(only("states"), 11, index);
    c.varyings[0].interpolation = Interpolation::smooth;  // the flat vec2 becomes smooth
    const CaseResult r = judge({c}).front();
    if (!failures_of(c, r).empty()) return {c, r};
  }
  ADD_FAILURE() << "no case of 200 fails the planted fault";
  return {};
}

TEST(Shrink, APlantedFaultShrinksToAKnownMinimalCase) {
  const auto [failing, result] = first_planted_failure();
  const std::vector<Failure> f = failures_of(failing, result);
  ASSERT_FALSE(f.empty());
  ASSERT_EQ(f.front().signature(), "non_finite/smooth");
  ASSERT_GT(failing.triangles.size(), 1u);

  int checks = 0;
  const Shrunk s = shrink(failing, result, f.front(), planted_judge(&checks));
  EXPECT_TRUE(s.complete);
  EXPECT_EQ(s.checks, checks);
  const Case& m = s.minimal;
  // The fault needs one triangle with a vertex at 0 < w_c < 1 and one smooth component: nothing
  // else is left, in a framebuffer of one pixel.
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.vertices.size(), 3u);
  ASSERT_EQ(m.varyings.size(), 1u);
  EXPECT_EQ(m.varyings[0].size, 1);
  EXPECT_EQ(m.varyings[0].interpolation, Interpolation::smooth);
  EXPECT_EQ(m.fb_width, 1);
  EXPECT_EQ(m.fb_height, 1);
  // Known: two vertices at infinity (w_c = 0) and the pixel centre's vertex at w_c = 0.25, every
  // value 0, every state GL's default. 0.25 stays: w_c = 1 would end the fault and no simpler
  // number than 0.25 that shrinking tries (0, 1, the nearest integer, fewer mantissa bits) keeps
  // it.
  const std::string text = casefile::to_case_file(m);
  EXPECT_EQ(text.substr(text.find("\"framebuffer\"")),
            std::string(R"("framebuffer": {"width": 1, "height": 1},
  "viewport": {"x": 0, "y": 0, "width": 1, "height": 1},
  "varyings": [
    {"name": "v1", "size": 1, "interpolation": "smooth"}
  ],
  "vertices": [
    {"clip": [1, 0, 0, 0], "v1": 0},
    {"clip": [0, 1, 0, 0], "v1": 0},
    {"clip": [0, 0, 0, 0.25], "v1": 0}
  ],
  "triangles": [
    [0, 1, 2]
  ]
}
)"));
  EXPECT_TRUE(shows(m, s.result, f.front()));
  // The same input shrinks to the same case.
  const Shrunk again = shrink(failing, result, f.front(), planted_judge());
  EXPECT_EQ(casefile::to_case_file(again.minimal), casefile::to_case_file(m));
}

TEST(Shrink, StopsAtItsBudgetWithTheSmallestCaseSoFar) {
  const auto [failing, result] = first_planted_failure();
  const Failure target = failures_of(failing, result).front();
  ShrinkOptions o;
  o.max_checks = 3;
  o.batch = 1;
  const Shrunk s = shrink(failing, result, target, planted_judge(), o);
  EXPECT_FALSE(s.complete);
  EXPECT_LE(s.checks, 3);
  EXPECT_TRUE(shows(s.minimal, s.result, target));
  EXPECT_LE(s.minimal.triangles.size(), failing.triangles.size());
}

TEST(Campaign, FindsThePlantedFaultOnceAndCountsWhatItChecked) {
  CampaignOptions o;
  o.seed = 5;
  o.count = 30;
  o.generators = only("states");
  o.batch = 7;
  int batches = 0;
  CampaignProgress progress;
  progress.batch_done = [&](const CampaignStats&, size_t) { ++batches; };
  // The states generator's first varying is flat: the fault needs a smooth one, which the
  // attributes generator makes too.
  o.generators = all_generators();
  const CampaignResult r = run_campaign(o, planted_judge(), progress);
  EXPECT_EQ(r.stats.cases, 30u);
  EXPECT_EQ(batches, 5);  // 7 + 7 + 7 + 7 + 2
  EXPECT_GT(r.stats.triangles, 30u);
  EXPECT_GT(r.stats.pixels, 1000u);
  ASSERT_GE(r.failures.size(), 1u);
  const FoundFailure* planted = nullptr;
  for (const FoundFailure& f : r.failures) {
    EXPECT_EQ(f.failure.kind, FailureClass::non_finite) << f.failure.signature();
    if (f.failure.signature() == "non_finite/smooth") planted = &f;
  }
  ASSERT_NE(planted, nullptr);
  EXPECT_EQ(planted->minimal.triangles.size(), 1u);
  EXPECT_EQ(planted->minimal.name, "non_finite_smooth");
  EXPECT_GE(planted->cases, 1u);
  EXPECT_EQ(planted->examples.front(), planted->index);
  // The minimal case is a case file the loader takes.
  EXPECT_NO_THROW(casefile::parse(casefile::to_case_file(planted->minimal), "m", "m"));

  // Two shards check the campaign's cases between them, each once.
  std::multiset<uint64_t> indices;
  for (int start = 1; start <= 2; ++start) {
    CampaignOptions shard = o;
    shard.fraction = 2, shard.fraction_start = start, shard.shrink = false;
    const CampaignResult s = run_campaign(shard, planted_judge());
    EXPECT_EQ(s.stats.cases, 15u);
    for (const FoundFailure& f : s.failures)
      for (const uint64_t k : f.examples)
        EXPECT_EQ(int(k % 2), start - 1);
  }
}

// Skipped cases are kept with their reasons: the first kSkippedExamples by index, as the
// campaign's results.json lists them, and the merge of shards lists the unsharded campaign's.
TEST(Campaign, KeepsTheFirstSkippedCasesWithTheirReasons) {
  // A judge that skips every third case, saying which.
  const Judge skipping = [](const std::vector<Case>& cases) {
    std::vector<CaseResult> out;
    for (const Case& c : cases) {
      CaseResult r;
      r.name = c.name;
      const bool skip = std::stoull(c.name.substr(c.name.rfind('_') + 1)) % 3 == 0;
      r.status = r.outcome = skip ? Status::skip : Status::pass;
      if (skip) r.message = "outside GL's specified range: " + c.name;
      out.push_back(r);
    }
    return out;
  };
  CampaignOptions o;
  o.seed = 4;
  o.count = 60;
  o.generators = only("states");
  o.batch = 8;
  const CampaignResult whole = run_campaign(o, skipping);
  EXPECT_EQ(whole.stats.skipped, 20u);
  ASSERT_EQ(whole.skipped.size(), kSkippedExamples);
  for (size_t k = 0; k < whole.skipped.size(); ++k) {
    EXPECT_EQ(whole.skipped[k].index, 3 * k);
    EXPECT_EQ(whole.skipped[k].generator, "states");
    EXPECT_EQ(whole.skipped[k].message,
              "outside GL's specified range: fuzz_states_4_" + std::to_string(3 * k));
  }
  const nlohmann::json json = campaign_json(whole, nlohmann::json::object());
  EXPECT_EQ(json["skipped"][1]["replay"], "glrefcheck fuzz --generator states --replay 4:3");

  std::vector<nlohmann::json> shards;
  std::vector<std::string> sources;
  for (int start = 1; start <= 2; ++start) {
    CampaignOptions shard = o;
    shard.fraction = 2, shard.fraction_start = start;
    // As `merge` reads them: from their files.
    shards.push_back(nlohmann::json::parse(
        campaign_json(run_campaign(shard, skipping), nlohmann::json::object()).dump()));
    sources.push_back("shard" + std::to_string(start));
  }
  std::vector<size_t> from;
  EXPECT_EQ(merge_campaigns(shards, sources, from)["skipped"], json["skipped"]);
}

}  // namespace
