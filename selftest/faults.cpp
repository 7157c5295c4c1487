#include "selftest/faults.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <utility>

namespace glrc::selftest {

namespace {

// The covered pixel with the largest |value| in component k (depth for k < 0), so that a
// relative change is visible; -1 when nothing is covered.
long largest_covered(const Frame& f, int k) {
  long best = -1;
  float best_value = -1;
  for (size_t i = 0; i < f.pixel_count(); ++i) {
    if (f.primitive[i] < 0) continue;
    const float v = std::fabs(k < 0 ? f.depth[i] : f.components[size_t(k)][i]);
    if (v > best_value) best = long(i), best_value = v;
  }
  return best;
}

std::vector<Fault> make_faults() {
  std::vector<Fault> list;

  list.push_back({"smooth-as-noperspective",
                  "perspective-correct varyings interpolated linearly in screen space",
                  [](Case& c) {
                    for (Varying& v : c.varyings)
                      if (v.interpolation == Interpolation::smooth)
                        v.interpolation = Interpolation::noperspective;
                  },
                  nullptr});

  list.push_back({"provoking-vertex-flipped",
                  "flat values taken from the other end of the triangle",
                  [](Case& c) {
                    c.provoking = c.provoking == ProvokingVertex::last ? ProvokingVertex::first
                                                                       : ProvokingVertex::last;
                  },
                  nullptr});

  list.push_back({"positions-shifted-half-pixel",
                  "window positions off by half a pixel in x (a pixel-centre convention error)",
                  [](Case& c) {
                    // x_w = (x_c / w_c + 1)·width/2 + x: half a pixel is w_c / width in x_c.
                    for (Vertex& v : c.vertices)
                      v.clip[0] = float(double(v.clip[0]) +
                                        double(v.clip[3]) / double(std::max(c.viewport.width, 1)));
                  },
                  nullptr});

  list.push_back({"depth-range-nudged", "glDepthRange applied 1e-4 off",
                  [](Case& c) {
                    // Inward, so that GL's clamping of the range to [0, 1] keeps the change.
                    auto nudge = [](float d) { return d <= 0.5f ? d + 1e-4f : d - 1e-4f; };
                    c.depth_near = nudge(c.depth_near);
                    c.depth_far = nudge(c.depth_far);
                  },
                  nullptr});

  list.push_back({"one-value-off-1e-3", "one value in one pixel changed by 1e-3 relative", nullptr,
                  [](const Case& c, const Expectation&, Frame& f) {
                    // The first interpolated component, or depth when there is none.
                    int k = -1;
                    const auto owner = component_varying(c);
                    for (size_t j = 0; j < owner.size() && k < 0; ++j)
                      if (c.varyings[size_t(owner[j])].interpolation != Interpolation::flat)
                        k = int(j);
                    const long i = largest_covered(f, k);
                    if (i < 0) return false;
                    float& v = k < 0 ? f.depth[size_t(i)] : f.components[size_t(k)][size_t(i)];
                    if (v == 0) return false;
                    v = float(double(v) * (1 + 1e-3));
                    return true;
                  }});

  list.push_back({"varyings-11-mantissa-bits",
                  "varyings carried at 11 mantissa bits (a half-float path) instead of 23", nullptr,
                  [](const Case&, const Expectation&, Frame& f) {
                    bool any = false;
                    for (auto& component : f.components)
                      for (size_t i = 0; i < component.size(); ++i) {
                        if (f.primitive[i] < 0) continue;
                        const float kept = keep_mantissa_bits(component[i], 11);
                        any = any || kept != component[i];
                        component[i] = kept;
                      }
                    return any;
                  }});

  list.push_back({"components-swapped", "two components of a varying swapped (x and y)", nullptr,
                  [](const Case& c, const Expectation&, Frame& f) {
                    int first = 0;
                    for (const Varying& v : c.varyings) {
                      if (v.size >= 2) {
                        std::swap(f.components[size_t(first)], f.components[size_t(first) + 1]);
                        return true;
                      }
                      first += v.size;
                    }
                    return false;
                  }});

  list.push_back({"shared-edge-pixel-dropped",
                  "one pixel on an edge two triangles share left uncovered (a crack in a mesh)",
                  nullptr, [](const Case&, const Expectation& e, Frame& f) {
                    for (size_t i = 0; i < f.pixel_count(); ++i) {
                      const uint8_t bits = e.edges[i];
                      if (!(bits & edge::shared) || (bits & edge::snapping) || f.primitive[i] < 0)
                        continue;
                      f.primitive[i] = Frame::kNoPrimitive;
                      f.depth[i] = 1.0f;
                      for (auto& component : f.components)
                        component[i] = 0.0f;
                      if (!f.fragments.empty()) f.fragments[i] = 0;
                      return true;
                    }
                    return false;
                  }});
  return list;
}

}  // namespace

const std::vector<Fault>& faults() {
  static const std::vector<Fault> list = make_faults();
  return list;
}

float keep_mantissa_bits(float x, int bits) {
  if (!std::isfinite(x) || bits >= 23) return x;
  // Round to nearest, ties to even, on the bit pattern: adding half of the dropped range (less
  // one when the kept part is even) carries into the kept bits exactly when rounding up.
  const uint32_t u = std::bit_cast<uint32_t>(x);
  const int drop = 23 - bits;
  const uint32_t half = (1u << (drop - 1)) - 1 + ((u >> drop) & 1);
  return std::bit_cast<float>((u + half) & ~((1u << drop) - 1));
}

}  // namespace glrc::selftest
