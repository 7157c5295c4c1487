// The shrinker of shrink.hpp. Each pass builds its candidates lazily (a 3,000-triangle fan has
// 3,000 one-triangle-fewer candidates, which are not all held at once), hands them to the judge
// a batch at a time, and keeps the first, in order, that still fails the same way.
#include "campaign/shrink.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <optional>

#include "casefile/casefile.hpp"
#include "casefile/write.hpp"
#include "core/primitive_assembly.hpp"
#include "selftest/faults.hpp"

namespace glrc::campaign {
namespace {

using Clock = std::chrono::steady_clock;

// Vertices no triangle uses are dropped and the rest renumbered in their order: the same
// drawing, a shorter file. Not for a case with draws, whose array draws name vertex ranges
// (Shrinker::draws first lowers such a case to its triangles where the failure allows).
void drop_unused_vertices(Case& c) {
  if (!c.draws.empty()) return;
  std::vector<int64_t> renumber(c.vertices.size(), -1);
  for (const auto& t : c.triangles)
    for (const uint32_t k : t)
      renumber[k] = 0;
  std::vector<Vertex> kept;
  for (size_t k = 0; k < c.vertices.size(); ++k)
    if (renumber[k] == 0)
      renumber[k] = int64_t(kept.size()), kept.push_back(std::move(c.vertices[k]));
  c.vertices = std::move(kept);
  for (auto& t : c.triangles)
    for (uint32_t& k : t)
      k = uint32_t(renumber[k]);
}

// The components of varying `v` that start at `first` and number `count` removed from every
// vertex, and the varying shortened (or removed when nothing is left of it).
Case without_components(const Case& c, size_t v, int first, int count) {
  Case out = c;
  int offset = 0;
  for (size_t k = 0; k < v; ++k)
    offset += c.varyings[k].size;
  for (Vertex& vertex : out.vertices) {
    const auto at = vertex.values.begin() + offset + first;
    vertex.values.erase(at, at + count);
  }
  out.varyings[v].size -= count;
  if (out.varyings[v].size == 0) out.varyings.erase(out.varyings.begin() + ptrdiff_t(v));
  return out;
}

// Simpler numbers than x, simplest first: 0, ±1, the nearest integer, x with fewer mantissa
// bits; each of strictly smaller complexity than x.
std::vector<float> simpler(float x) {
  std::vector<float> out;
  auto add = [&](float y) {
    if (!std::isfinite(y) || complexity(y) >= complexity(x)) return;
    for (const float z : out)
      if (std::bit_cast<uint32_t>(z) == std::bit_cast<uint32_t>(y)) return;
    out.push_back(y);
  };
  add(0.0f);
  add(std::copysign(1.0f, x));
  if (std::fabs(x) < 0x1p24f) add(std::nearbyint(x));
  for (const int bits : {0, 1, 2, 3, 4, 6, 8, 12, 16})
    add(selftest::keep_mantissa_bits(x, bits));
  std::stable_sort(out.begin(), out.end(),
                   [](float a, float b) { return complexity(a) < complexity(b); });
  return out;
}

// Whether the case loader takes `c` as its case file: a smaller case can break one of the
// format's rules (a w_c of 0 under a noperspective varying, say), and a minimal case must be one
// anybody can run and put into cases/.
bool loadable(const Case& c) {
  try {
    casefile::parse(casefile::to_case_file(c), "candidate", c.name);
    return true;
  } catch (const casefile::CaseError&) {
    return false;
  }
}

class Shrinker {
 public:
  Shrinker(const Failure& target, const Judge& judge, const ShrinkOptions& o)
      : target_(target), judge_(judge), o_(o), start_(Clock::now()) {}

  Shrunk out;

  bool budget_left() const {
    return seconds() < o_.seconds && out.checks < o_.max_checks && !(o_.stop && o_.stop());
  }
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  // Candidates make(0), ..., make(count - 1), nullopt for one not worth checking; the first
  // that still fails becomes the minimal case. Whether one did.
  template <class Make>
  bool first_failing(size_t count, Make make) {
    size_t next = 0;
    while (next < count && budget_left()) {
      std::vector<Case> batch;
      while (next < count && batch.size() < std::max<size_t>(o_.batch, 1))
        if (std::optional<Case> c = make(next++); c && loadable(*c)) batch.push_back(std::move(*c));
      if (batch.empty()) break;
      const std::vector<CaseResult> results = judge_(batch);
      out.checks += int(batch.size());
      for (size_t k = 0; k < batch.size() && k < results.size(); ++k)
        if (shows(batch[k], results[k], target_)) {
          out.minimal = std::move(batch[k]);
          out.result = results[k];
          ++out.steps;
          return true;
        }
    }
    return false;
  }

  // A case with draws (strips, fans, restarts, several draws): a draw left out; the whole case
  // as the one GL_TRIANGLES list of its triangles (which the other passes then shrink, when
  // the failure does not need the assembly); a draw's last vertex or index left out.
  bool draws() {
    bool progress = false;
    for (bool kept = true; kept && !out.minimal.draws.empty() && budget_left();) {
      const Case& m = out.minimal;
      const size_t n = m.draws.size();
      kept = first_failing(2 * n + 1, [&](size_t i) -> std::optional<Case> {
        Case c = m;
        if (i == n) {
          c.draws.clear();  // c.triangles stay: the list GL assembled
          drop_unused_vertices(c);
          return c;
        }
        if (i < n) {
          if (n == 1) return std::nullopt;
          c.draws.erase(c.draws.begin() + ptrdiff_t(i));
        } else if (Draw& d = c.draws[i - n - 1]; d.indexed()) {
          if (d.indices.size() <= 1) return std::nullopt;
          d.indices.pop_back();
        } else {
          if (d.count <= 1) return std::nullopt;
          --d.count;
        }
        assemble_triangles(c);
        if (c.triangles.empty()) return std::nullopt;
        return c;
      });
      progress = progress || kept;
    }
    return progress;
  }

  bool triangles() {
    bool progress = false;
    // A case with draws shrinks by draws() (its triangles are the draws' assembly).
    if (!out.minimal.draws.empty()) return false;
    size_t chunk = std::max<size_t>(out.minimal.triangles.size() / 2, 1);
    while (out.minimal.triangles.size() > 1 && budget_left()) {
      const Case& m = out.minimal;
      const size_t n = m.triangles.size();
      chunk = std::min(chunk, std::max<size_t>(n / 2, 1));
      const size_t count = (n + chunk - 1) / chunk;
      const bool kept = first_failing(count, [&](size_t i) -> std::optional<Case> {
        Case c = m;
        const auto from = c.triangles.begin() + ptrdiff_t(i * chunk);
        c.triangles.erase(from, from + ptrdiff_t(std::min(chunk, n - i * chunk)));
        drop_unused_vertices(c);
        return c;
      });
      progress = progress || kept;
      if (!kept) {
        if (chunk == 1) break;
        chunk /= 2;
      }
    }
    return progress;
  }

  bool varyings() {
    bool progress = false;
    for (bool kept = true; kept && !out.minimal.varyings.empty() && budget_left();) {
      const Case& m = out.minimal;
      kept = first_failing(m.varyings.size(), [&](size_t v) -> std::optional<Case> {
        return without_components(m, v, 0, m.varyings[v].size);
      });
      progress = progress || kept;
    }
    for (bool kept = true; kept && budget_left();) {
      const Case& m = out.minimal;
      kept = first_failing(2 * m.varyings.size(), [&](size_t i) -> std::optional<Case> {
        const size_t v = i / 2;
        const int size = m.varyings[v].size;
        if (size == 1 || m.varyings[v].is_builtin()) return std::nullopt;  // a built-in's is fixed
        return without_components(m, v, i % 2 == 0 ? size - 1 : 0, 1);     // the last, the first
      });
      progress = progress || kept;
    }
    return progress;
  }

  // GL's defaults for every state, one at a time: a state the failure does not need is noise.
  bool states() {
    bool progress = false;
    for (bool kept = true; kept && budget_left();) {
      const Case& m = out.minimal;
      kept = first_failing(10, [&](size_t i) -> std::optional<Case> {
        Case c = m;
        const Case defaults;
        switch (i) {
          case 7:  // no clip or cull distances
            c.distances = {};
            for (Vertex& v : c.vertices)
              v.distances.clear();
            break;
          case 5:  // the same window image and facing under GL_LOWER_LEFT: y_c negated
            if (c.clip_origin == defaults.clip_origin) break;
            c.clip_origin = defaults.clip_origin;
            for (Vertex& v : c.vertices)
              v.clip[1] = -v.clip[1];
            c.front_face = c.front_face == FrontFace::ccw ? FrontFace::cw : FrontFace::ccw;
            break;
          case 6:
            c.clip_depth = defaults.clip_depth;
            break;
          case 0:
            c.cull = defaults.cull;
            break;
          case 1:
            c.front_face = defaults.front_face;
            break;
          case 2:
            c.provoking = defaults.provoking;
            assemble_triangles(c);  // strips and fans assemble by the convention
            break;
          case 3:
            c.depth_func = defaults.depth_func;
            break;
          case 4:
            c.depth_near = defaults.depth_near, c.depth_far = defaults.depth_far;
            break;
          case 8:
            c.depth_clamp = defaults.depth_clamp;
            break;
          case 9:  // the polygon offset's clamp first, then the whole offset
            if (c.polygon_offset && c.polygon_offset->clamp)
              c.polygon_offset->clamp.reset();
            else
              c.polygon_offset.reset();
            break;
        }
        if (casefile::to_case_file(c) == casefile::to_case_file(m)) return std::nullopt;
        return c;
      });
      progress = progress || kept;
    }
    return progress;
  }

  bool framebuffer() {
    bool progress = false;
    for (bool kept = true; kept && budget_left();) {
      const Case& m = out.minimal;
      const Viewport v = m.viewport;
      kept = first_failing(4, [&](size_t i) -> std::optional<Case> {
        Case c = m;
        switch (i) {
          case 0: {  // the viewport at the origin, the framebuffer just holding it: the same
                     // drawing, moved by whole pixels (a fractional origin keeps its fraction)
            const float x = v.x - std::floor(v.x), y = v.y - std::floor(v.y);
            const int width = int(std::ceil(x + v.width)), height = int(std::ceil(y + v.height));
            if (v.x == x && v.y == y && c.fb_width == width && c.fb_height == height)
              return std::nullopt;
            c.viewport.x = x, c.viewport.y = y;
            c.fb_width = width, c.fb_height = height;
            return c;
          }
          case 1:  // both halved
          case 2:  // the width halved
          case 3:  // the height halved
            if ((i != 3 && v.width < 2) || (i != 2 && v.height < 2)) return std::nullopt;
            // Whole numbers stay whole (halved toward 0, as integers are); fractions halve.
            const auto half = [](float f) {
              return f == std::floor(f) ? std::trunc(f / 2) : f / 2;
            };
            if (i != 3)
              c.viewport.x = half(c.viewport.x), c.viewport.width = half(c.viewport.width),
              c.fb_width = (c.fb_width + 1) / 2;
            if (i != 2)
              c.viewport.y = half(c.viewport.y), c.viewport.height = half(c.viewport.height),
              c.fb_height = (c.fb_height + 1) / 2;
            c.fb_width = std::max(c.fb_width, int(std::ceil(c.viewport.x + c.viewport.width)));
            c.fb_height = std::max(c.fb_height, int(std::ceil(c.viewport.y + c.viewport.height)));
            return c;
        }
        return std::nullopt;
      });
      progress = progress || kept;
    }
    return progress;
  }

  // Every number of the case (clip coordinates, then values), as a pointer into `c`.
  static std::vector<float*> numbers(Case& c) {
    std::vector<float*> all;
    for (Vertex& v : c.vertices) {
      for (float& x : v.clip)
        all.push_back(&x);
      for (float& x : v.values)
        all.push_back(&x);
    }
    return all;
  }

  bool numbers() {
    bool progress = false;
    // First the whole case at once, to fewer mantissa bits: one check may do most of the work.
    {
      const Case& m = out.minimal;
      static constexpr int kBits[] = {0, 2, 4, 8, 12};
      progress = first_failing(std::size(kBits), [&](size_t i) -> std::optional<Case> {
        Case c = m;
        bool changed = false;
        for (float* x : numbers(c)) {
          const float y = selftest::keep_mantissa_bits(*x, kBits[i]);
          if (std::isfinite(y) && complexity(y) < complexity(*x)) *x = y, changed = true;
        }
        return changed ? std::optional<Case>(std::move(c)) : std::nullopt;
      });
    }
    // Then each vertex's position to w = 1 (the same window position, affine), and each number
    // on its own, simplest replacement first.
    for (size_t at = 0; budget_left(); ++at) {
      Case probe = out.minimal;
      const size_t count = numbers(probe).size();
      if (at >= count) break;
      const size_t per_vertex = 4 + size_t(out.minimal.component_count());
      if (at % per_vertex == 0) {
        const size_t vertex = at / per_vertex;
        const bool kept = first_failing(1, [&](size_t) -> std::optional<Case> {
          Case c = out.minimal;
          auto& p = c.vertices[vertex].clip;
          if (p[3] == 1 || !(p[3] > 0)) return std::nullopt;
          const double w = p[3];
          p = {float(p[0] / w), float(p[1] / w), float(p[2] / w), 1.0f};
          return c;
        });
        progress = progress || kept;
      }
      const float x = *numbers(probe)[at];
      const std::vector<float> candidates = simpler(x);
      const bool kept = first_failing(candidates.size(), [&](size_t i) -> std::optional<Case> {
        Case c = out.minimal;
        *numbers(c)[at] = candidates[i];
        return c;
      });
      progress = progress || kept;
    }
    return progress;
  }

 private:
  const Failure& target_;
  const Judge& judge_;
  const ShrinkOptions& o_;
  Clock::time_point start_;
};

}  // namespace

int complexity(float x) {
  if (x == 0) return std::signbit(x) ? 1 : 0;
  if (!std::isfinite(x)) return 1 << 20;
  const uint32_t u = std::bit_cast<uint32_t>(x);
  const int biased = int((u >> 23) & 0xff);
  const uint32_t significand = (u & 0x7fffff) | (biased ? 0x800000u : 0);
  const int exponent = (biased ? biased : 1) - 150;  // x = significand · 2^exponent
  const int trailing = std::countr_zero(significand);
  const int bits = 24 - trailing;
  const bool integer = exponent + trailing >= 0;
  const int binade = biased ? biased - 127 : -127;
  return 2 + 4 * bits + 2 * std::abs(binade) + (integer ? 0 : 16) + (x < 0 ? 1 : 0);
}

bool shows(const Case& c, const CaseResult& r, const Failure& target) {
  for (const Failure& f : failures_of(c, r))
    if (f == target) return true;
  return false;
}

Shrunk shrink(const Case& failing, const CaseResult& failing_result, const Failure& target,
              const Judge& judge, const ShrinkOptions& options) {
  Shrinker s(target, judge, options);
  s.out.minimal = failing;
  s.out.result = failing_result;
  drop_unused_vertices(s.out.minimal);
  for (bool progress = true; progress && s.budget_left();) {
    progress = s.draws();
    progress = s.triangles() || progress;
    progress = s.varyings() || progress;
    progress = s.states() || progress;
    progress = s.framebuffer() || progress;
    progress = s.numbers() || progress;
  }
  s.out.complete = s.budget_left();
  s.out.seconds = s.seconds();
  return s.out;
}

}  // namespace glrc::campaign
