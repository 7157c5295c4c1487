// The terminal reports: one line per case for `run`, the statistics and worst-pixel tables for
// `diff`. Fixed-width so that runs line up and can be diffed.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "report/coverage_image.hpp"
#include "report/format.hpp"
#include "report/report.hpp"

namespace glrc::report {
namespace {

// Wide enough for "UnexpectedPass", the longest status.
constexpr int kStatusWidth = 14;
constexpr int kNameWidth = 28;
// The listing shows the start of a longer message; all of it is in results.json.
constexpr size_t kShortMessage = 100;

// The largest value of a channel statistic over all channels, as text, or "NaN" when GL gave a
// non-finite value somewhere: that is worse than any finite error and must not hide behind one.
template <typename Field, typename Format>
std::string worst_text(const CaseResult& r, Field field, Format format) {
  if (r.channels.empty()) return "-";
  double worst = 0;
  for (const auto& ch : r.channels) {
    if (ch.non_finite > 0) return "NaN";
    worst = std::max(worst, ch.*field);
  }
  return format(worst);
}

}  // namespace

std::string case_line(const CaseResult& r) {
  std::string line =
      fmt::format("{:<{}} {:<{}} max {:>5} ulp {:>6}x allowed  coverage {} bad, {} at edges  {}",
                  to_string(r.status), kStatusWidth, r.name, kNameWidth,
                  worst_text(r, &ChannelStats::max_ulps, ulps_text),
                  worst_text(r, &ChannelStats::max_ratio, ratio_text), r.coverage.failures,
                  r.coverage.boundary, seconds_text(r.seconds));
  const std::string message = short_message(r.message, kShortMessage);
  if (r.status != Status::pass && !message.empty()) line += "  " + message;
  return line;
}

std::string stats_table(const CaseResult& r) {
  size_t name_width = 7;
  for (const auto& ch : r.channels)
    name_width = std::max(name_width, ch.name.size());

  const auto row = [&](auto&& channel, auto&& compared, auto&& max_abs, auto&& max_ulp, auto&& mean,
                       auto&& p99, auto&& max_ratio, auto&& p99_ratio, auto&& over,
                       auto&& tolerance, auto&& verdict) {
    return fmt::format(
        "{:<{}}  {:>9}  {:>11}  {:>9}  {:>8}  {:>8}  {:>9}  {:>9}  {:>8}  {:>11}  {}\n", channel,
        name_width, compared, max_abs, max_ulp, mean, p99, max_ratio, p99_ratio, over, tolerance,
        verdict);
  };
  // spec: the allowance varies per pixel; its largest value is shown, in ulp.
  const bool spec = r.tolerance.mode == ToleranceMode::spec;
  std::string table = row("channel", "compared", "max abs", "max ulp", "mean", "p99", "max/allow",
                          "p99/allow", "over", spec ? "allow<=ulp" : "tolerance", "verdict");
  for (const auto& ch : r.channels) {
    std::string verdict = ch.pass() ? "ok" : "FAIL";
    if (ch.non_finite > 0) verdict += fmt::format(" ({} non-finite)", ch.non_finite);
    if (r.tolerance.mode == ToleranceMode::exact)
      verdict += fmt::format(" ({} px differ)", ch.differing);
    table +=
        row(ch.name, ch.compared, fmt::format("{:.3g}", ch.max_abs), ulps_text(ch.max_ulps),
            ulps_text(ch.mean_ulps), ulps_text(ch.p99_ulps), ratio_text(ch.max_ratio),
            ratio_text(ch.p99_ratio), ch.over_tolerance, ulps_text(ch.tolerance_ulps), verdict);
  }
  const auto& cov = r.coverage;
  table += fmt::format(
      "coverage: both {}, reference only {}, GL only {}, other primitive {}; mismatches: "
      "exact tie {}, within snapping {}, fill-rule error {}; shared edges: gaps {}, double hits "
      "{}{}{}; failures {}{}\n",
      cov.both, cov.reference_only, cov.gl_only, cov.other_primitive, cov.exact_tie,
      cov.within_snapping, cov.fill_rule, cov.gaps, cov.double_hits,
      cov.fragments_checked ? "" : " (no fragment counts)",
      cov.counts_traced + cov.counts_untraced == 0
          ? ""
          : fmt::format("; counts in bands traced to triangles {}, untraced {}", cov.counts_traced,
                        cov.counts_untraced),
      cov.failures, r.tolerance.allow_boundary ? " (ties and snapping allowed)" : "");
  return table;
}

std::string worst_pixels_table(const CaseResult& r, size_t n) {
  struct Entry {
    const std::string* channel;
    const WorstPixel* pixel;
  };
  std::vector<Entry> entries;
  for (const auto& ch : r.channels)
    for (const auto& w : ch.worst)
      entries.push_back({&ch.name, &w});

  // Non-finite errors first (NaN before inf), then the largest finite ones; stable so that
  // ties keep the channel order (depth first).
  const auto rank = [](double ulps) { return std::isnan(ulps) ? 0 : std::isinf(ulps) ? 1 : 2; };
  // Ranked by the share of the allowance used: that is what decides the verdict.
  std::stable_sort(entries.begin(), entries.end(), [&](const Entry& a, const Entry& b) {
    const double ua = a.pixel->ulps, ub = b.pixel->ulps;
    if (rank(ua) != rank(ub)) return rank(ua) < rank(ub);
    if (rank(ua) != 2) return false;
    if (a.pixel->ratio != b.pixel->ratio) return a.pixel->ratio > b.pixel->ratio;
    return ua > ub;
  });
  if (entries.size() > n) entries.resize(n);
  if (entries.empty()) return "";

  size_t name_width = 7;
  for (const auto& e : entries)
    name_width = std::max(name_width, e.channel->size());
  const auto row = [&](auto&& x, auto&& y, auto&& channel, auto&& ref, auto&& gl, auto&& abs,
                       auto&& ulps, auto&& allowed, auto&& ratio) {
    return fmt::format("{:>5} {:>5}  {:<{}}  {:>16}  {:>16}  {:>16}  {:>10}  {:>16}  {:>9}\n", x, y,
                       channel, name_width, ref, gl, abs, ulps, allowed, ratio);
  };
  // x, y are GL window coordinates (row 0 at the bottom), as everywhere in the results.
  std::string table =
      row("x", "y", "channel", "reference", "GL", "abs error", "ulps", "allowed", "error/allow");
  for (const auto& e : entries)
    table += row(e.pixel->x, e.pixel->y, *e.channel, float_text(e.pixel->reference),
                 float_text(e.pixel->gl), float_text(e.pixel->abs_error),
                 std::isfinite(e.pixel->ulps) ? fmt::format("{:.6g}", e.pixel->ulps)
                                              : ulps_text(e.pixel->ulps),
                 float_text(float(e.pixel->allowed)), ratio_text(e.pixel->ratio));
  return table;
}

std::string coverage_failures_table(const CaseResult& r, const Frame& reference, const Frame& gl,
                                    size_t n) {
  const CoverageStats& cov = r.coverage;
  if (cov.failures == 0) return "";
  const bool explained_fail = explained_mismatches_fail(r.tolerance);
  const auto primitive_text = [](int32_t p) {
    return p == Frame::kNoPrimitive ? std::string("-") : std::to_string(p);
  };
  const auto fragments_text = [](const Frame& f, int x, int y) {
    if (f.fragments.size() != f.pixel_count() || x < 0 || y < 0 || x >= f.width || y >= f.height)
      return std::string("-");
    return std::to_string(f.fragments[f.index(x, y)]);
  };
  const auto row = [](auto&& x, auto&& y, auto&& ref_p, auto&& gl_p, auto&& ref_f, auto&& gl_f,
                      auto&& label) {
    return fmt::format("{:>5} {:>5}  {:>9}  {:>9}  {:>9}  {:>9}  {}\n", x, y, ref_p, gl_p, ref_f,
                       gl_f, label);
  };
  // x, y are GL window coordinates (row 0 at the bottom), as everywhere in the results.
  std::string table = row("x", "y", "ref prim", "GL prim", "ref frags", "GL frags", "coverage");
  size_t shown = 0;
  for (const auto& p : cov.mismatches) {
    if (p.boundary && !explained_fail) continue;  // allowed: not a failure
    if (shown == n) break;
    ++shown;
    table +=
        row(p.x, p.y, primitive_text(p.reference), primitive_text(p.gl),
            fragments_text(reference, p.x, p.y), fragments_text(gl, p.x, p.y), label_text(p.label));
  }
  if (cov.failures > shown)
    table +=
        fmt::format("{} (coverage.png rings every failing pixel)\n",
                    count_text(cov.failures - shown, "more failing pixel", "more failing pixels"));
  return table;
}

}  // namespace glrc::report
