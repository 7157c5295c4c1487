#include "report/html.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "report/base64.hpp"
#include "report/format.hpp"
#include "report/stamp.hpp"

namespace glrc::report {
namespace {

namespace fs = std::filesystem;

// A fragment link must be percent-encoded to reach an id holding spaces or reserved characters.
std::string fragment(std::string_view text) {
  std::string out;
  for (unsigned char c : text) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.') {
      out += static_cast<char>(c);
    } else {
      out += fmt::format("%{:02X}", c);
    }
  }
  return out;
}

constexpr const char* kStyle = R"(<style>
body { font-family: sans-serif; font-size: 14px; margin: 1.5em; color: #222; }
h1 { font-size: 1.5em; }
h2 { font-size: 1.25em; margin-top: 2em; border-bottom: 1px solid #ccc; }
h3 { font-size: 1.1em; margin-top: 1.5em; }
table { border-collapse: collapse; margin: 0.5em 0; }
th, td { border: 1px solid #ccc; padding: 2px 8px; text-align: left; vertical-align: top; }
th { background: #eee; }
td.num { text-align: right; font-family: monospace; }
table.summary th { text-align: left; font-weight: normal; color: #555; background: none; }
.counts span { display: inline-block; margin-right: 1em; padding: 1px 6px; }
.mono { font-family: monospace; }
.message { font-family: monospace; white-space: pre-wrap; }
figure { display: inline-block; margin: 0.5em; vertical-align: top; }
figure img { max-width: 100%; image-rendering: pixelated; border: 1px solid #ccc; }
figcaption { font-family: monospace; font-size: 0.9em; color: #555; }
td.image { text-align: center; }
td.image img { max-width: 100%; image-rendering: pixelated; }
.s-Pass { background: #e6f4e6; }
.s-Fail, .s-Error { background: #f8d7d7; }
.s-Crash, .s-Timeout { background: #f0b4b4; }
.s-ExpectedFail { background: #fdf0d5; }
.s-UnexpectedPass { background: #e8dcf4; }
.s-Flake { background: #fff7b3; }
.s-Skip { background: #eeeeee; color: #666; }
.k-regression { background: #f8d7d7; }
.k-fix { background: #e6f4e6; }
.k-changed { background: #fdf0d5; }
.k-precision { background: #fff7b3; }
.k-added, .k-removed { background: #e3ecf7; }
.k-skipped { background: #eeeeee; color: #666; }
</style>
)";

// Lets a test (or a curious reader, in the console) confirm that every embedded image decodes.
constexpr const char* kScript = R"(<script>
window.addEventListener('load', function () {
  var images = document.images, loaded = 0;
  for (var i = 0; i < images.length; i++) {
    if (images[i].complete && images[i].naturalWidth > 0) loaded++;
  }
  document.body.dataset.imagesLoaded = loaded;
  document.body.dataset.imagesTotal = images.length;
});
</script>
)";

// `writer`: the command the stamp names ("report" for a run's page, "compare").
void begin_page(std::ostream& out, const std::string& title, const char* writer) {
  // The stamp (report/stamp.hpp): a later write replaces this page only while it is unchanged.
  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      << "<meta name=\"generator\" content=\"glrefcheck " << writer << " " << stamp_placeholder()
      << "\">\n<title>" << xml_escaped(title) << "</title>\n"
      << kStyle << "</head>\n<body>\n<h1>" << xml_escaped(title) << "</h1>\n";
}

void end_page(std::ostream& out) {
  out << kScript << "</body>\n</html>\n";
}

// Written in one piece at the end, so a failed write never leaves half a report behind a
// successful return.
void write_file(const fs::path& file, const std::string& text) {
  write_file_atomically(file, stamped(text));
}

std::string read_binary(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The case's heatmap folder, or empty where the name could climb out of `run_dir/cases`.
fs::path case_dir(const fs::path& run_dir, const std::string& name) {
  if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos) {
    return {};
  }
  return run_dir / "cases" / name;
}

// The PNGs of a case folder, in reading order: each channel's error, allowed and ratio maps in
// the case's channel order, then coverage, then anything else by name.
std::vector<std::string> png_names(const fs::path& dir, const std::vector<std::string>& channels) {
  std::set<std::string> present;
  std::error_code ec;
  if (dir.empty() || !fs::is_directory(dir, ec)) return {};
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.is_regular_file(ec) && entry.path().extension() == ".png") {
      present.insert(entry.path().filename().string());
    }
  }
  std::vector<std::string> ordered;
  auto take = [&](const std::string& name) {
    if (present.erase(name) > 0) ordered.push_back(name);
  };
  for (const auto& ch : channels) {
    for (const char* suffix : {"_error.png", "_allowed.png", "_ratio.png"})
      take(ch + suffix);
  }
  take("coverage.png");
  ordered.insert(ordered.end(), present.begin(), present.end());
  return ordered;
}

std::string img_tag(const fs::path& png, const std::string& alt) {
  return "<img src=\"data:image/png;base64," + base64_encode(read_binary(png)) + "\" alt=\"" +
         xml_escaped(alt) + "\">";
}

std::string figure(const fs::path& png) {
  const std::string name = png.filename().string();
  return "<figure>" + img_tag(png, name) + "<figcaption>" + xml_escaped(name) +
         "</figcaption></figure>\n";
}

std::string status_cell(Status s) {
  return fmt::format("<td class=\"s-{0}\">{0}</td>", to_string(s));
}

// NaN is the worst error there is: it wins the maximum instead of vanishing from it.
double worst(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::nan("");
  return std::max(a, b);
}

bool is_failing(const CaseResult& r) {
  auto ok = [](Status s) { return s == Status::pass || s == Status::skip; };
  return !ok(r.status) || !ok(r.outcome);
}

constexpr std::array kStatusOrder = {
    Status::pass,  Status::fail,    Status::expected_fail, Status::unexpected_pass,
    Status::crash, Status::timeout, Status::flake,         Status::skip,
    Status::error};

void run_summary(std::ostream& out, const RunResults& results) {
  const RunInfo& run = results.run;
  out << "<table class=\"summary\">\n";
  auto row = [&](const char* label, const std::string& value) {
    out << "<tr><th>" << label << "</th><td>" << xml_escaped(value) << "</td></tr>\n";
  };
  row("GL_RENDERER", run.gl_renderer);
  row("GL_VERSION", run.gl_version);
  row("GL_VENDOR", run.gl_vendor);
  if (!run.mesa_prefix.empty()) row("Mesa prefix", run.mesa_prefix);
  if (!run.gl_library.empty()) row("GL library", run.gl_library);
  for (const std::string& w : run.gl_warnings)
    row("GL warning", w);
  row("model", run.model);
  if (!run.model_source.empty()) row("model from", run.model_source);
  row("tolerance", run.tolerance);
  row("jobs", std::to_string(run.jobs));
  row("wall time", seconds_text(run.seconds));
  if (run.interrupted)
    row("interrupted",
        fmt::format("by a signal after {} cases; `glrefcheck run --resume` completes the run",
                    results.cases.size()));
  out << "</table>\n<p class=\"counts\">";
  for (Status s : kStatusOrder) {
    const auto n = std::count_if(results.cases.begin(), results.cases.end(),
                                 [s](const CaseResult& r) { return r.status == s; });
    if (n > 0) out << fmt::format("<span class=\"s-{0}\">{0}: {1}</span>", to_string(s), n);
  }
  out << fmt::format("<span>total: {}</span></p>\n", results.cases.size());
}

void case_table(std::ostream& out, const std::vector<CaseResult>& cases) {
  out << "<h2>Cases</h2>\n<table class=\"cases\">\n<tr><th>case</th><th>status</th>"
         "<th>outcome</th><th>max error (ulp)</th><th>max / allowed</th>"
         "<th>coverage failures</th><th>seconds</th><th>message</th></tr>\n";
  for (const CaseResult& r : cases) {
    std::string ulps, ratio;
    if (!r.channels.empty()) {
      double max_ulps = 0, max_ratio = 0;
      for (const auto& ch : r.channels) {
        max_ulps = worst(max_ulps, ch.max_ulps);
        max_ratio = worst(max_ratio, ch.max_ratio);
      }
      ulps = ulps_text(max_ulps);
      ratio = ratio_text(max_ratio);
    }
    std::string name = xml_escaped(r.name);
    if (is_failing(r)) {
      name = "<a href=\"#detail-" + fragment(r.name) + "\">" + name + "</a>";
    }
    out << fmt::format(
        "<tr id=\"case-{}\" class=\"s-{}\"><td>{}</td>{}{}<td class=\"num\">{}</td>"
        "<td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{:.3f}</td>"
        "<td class=\"message\">{}</td></tr>\n",
        xml_escaped(r.name), to_string(r.status), name, status_cell(r.status),
        status_cell(r.outcome), ulps, ratio, r.coverage.failures, r.seconds,
        xml_escaped(r.message));
  }
  out << "</table>\n";
}

void channel_table(std::ostream& out, const CaseResult& r) {
  if (r.channels.empty()) return;
  out << "<table class=\"channels\">\n<tr><th>channel</th><th>compared</th>"
         "<th>over tolerance</th><th>non-finite</th><th>max ulps</th><th>p99 ulps</th>"
         "<th>max / allowed</th><th>p99 / allowed</th></tr>\n";
  for (const auto& ch : r.channels) {
    out << fmt::format(
        "<tr class=\"s-{}\"><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
        "<td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
        "<td class=\"num\">{}</td><td class=\"num\">{}</td></tr>\n",
        ch.pass() ? "Pass" : "Fail", xml_escaped(ch.name), ch.compared, ch.over_tolerance,
        ch.non_finite, ulps_text(ch.max_ulps), ulps_text(ch.p99_ulps), ratio_text(ch.max_ratio),
        ratio_text(ch.p99_ratio));
  }
  out << "</table>\n";
}

std::vector<std::string> channel_names(const std::vector<ChannelStats>& channels) {
  std::vector<std::string> names;
  for (const auto& ch : channels)
    names.push_back(ch.name);
  return names;
}

void case_detail(std::ostream& out, const CaseResult& r, const fs::path& run_dir) {
  out << fmt::format("<h3 id=\"detail-{}\" class=\"s-{}\">{} — {}</h3>\n", xml_escaped(r.name),
                     to_string(r.status), xml_escaped(r.name), to_string(r.status));
  if (!r.message.empty()) out << "<p class=\"message\">" << xml_escaped(r.message) << "</p>\n";
  const CoverageStats& cov = r.coverage;
  if (cov.failures > 0) {
    out << fmt::format("<p>Coverage: {} (fill rule {}, gaps {}, double hits {}).</p>\n",
                       count_text(cov.failures, "failing pixel", "failing pixels"), cov.fill_rule,
                       cov.gaps, cov.double_hits);
  }
  channel_table(out, r);
  const fs::path dir = case_dir(run_dir, r.name);
  const auto pngs = png_names(dir, channel_names(r.channels));
  if (pngs.empty()) {
    out << "<p>No heatmaps in <code>" << xml_escaped((run_dir / "cases" / r.name).string())
        << "</code>.</p>\n";
    return;
  }
  out << "<div class=\"images\">\n";
  for (const auto& png : pngs)
    out << figure(dir / png);
  out << "</div>\n";
}

// ---- comparison ----

std::string status_text(const std::optional<Status>& s) {
  return s ? to_string(*s) : "—";
}

std::string grown_channels(const CaseChange& c) {
  std::string text;
  for (const auto& ch : c.channels) {
    if (!ch.max_grew && !ch.p99_grew) continue;
    if (!text.empty()) text += "<br>";
    if (ch.max_grew) {
      text += fmt::format("{}: {} → {} ulp", xml_escaped(ch.channel), ulps_text(ch.base_max_ulps),
                          ulps_text(ch.current_max_ulps));
    } else {
      text += fmt::format("{}: p99 {} → {} ulp", xml_escaped(ch.channel),
                          ulps_text(ch.base_p99_ulps), ulps_text(ch.current_p99_ulps));
    }
  }
  return text;
}

void comparison_header(std::ostream& out, const RunComparison& c) {
  out << "<table class=\"summary\">\n<tr><th></th><th>base</th><th>current</th></tr>\n";
  auto row = [&](const char* label, const std::string& base, const std::string& current) {
    out << "<tr><th>" << label << "</th><td>" << xml_escaped(base) << "</td><td>"
        << xml_escaped(current) << "</td></tr>\n";
  };
  row("GL_VERSION", c.base.gl_version, c.current.gl_version);
  row("GL_RENDERER", c.base.gl_renderer, c.current.gl_renderer);
  row("backend", c.base.backend, c.current.backend);
  row("driver", c.base.driver, c.current.driver);
  if (!c.base.mesa_prefix.empty() || !c.current.mesa_prefix.empty()) {
    row("Mesa prefix", c.base.mesa_prefix, c.current.mesa_prefix);
  }
  if (!c.base.gl_library.empty() || !c.current.gl_library.empty()) {
    row("GL library", c.base.gl_library, c.current.gl_library);
  }
  out << "</table>\n";
  out << fmt::format(
      "<p>Precision changes: error grown more than {}× (errors under {} ulp "
      "count as {} ulp).</p>\n",
      c.factor, c.min_ulps, c.min_ulps);
  out << "<p>" << xml_escaped(bits_summary(c)) << ".</p>\n";
}

constexpr std::array kKindOrder = {CaseChange::Kind::regression, CaseChange::Kind::fix,
                                   CaseChange::Kind::changed,    CaseChange::Kind::precision,
                                   CaseChange::Kind::added,      CaseChange::Kind::removed,
                                   CaseChange::Kind::skipped,    CaseChange::Kind::unchanged};

bool shows_images(CaseChange::Kind k) {
  return k == CaseChange::Kind::regression || k == CaseChange::Kind::changed ||
         k == CaseChange::Kind::precision;
}

// A changed case's heatmaps in both runs; `names` is their union, one row each, so the same map
// of both runs sits on one line.
struct ChangeImages {
  fs::path base, current;
  std::vector<std::string> base_pngs, current_pngs, names;
};

ChangeImages change_images(const CaseChange& c, const fs::path& base_dir,
                           const fs::path& current_dir) {
  std::vector<std::string> channels;
  for (const auto& ch : c.channels)
    channels.push_back(ch.channel);
  ChangeImages images;
  images.base = case_dir(base_dir, c.name);
  images.current = case_dir(current_dir, c.name);
  images.base_pngs = png_names(images.base, channels);
  images.current_pngs = png_names(images.current, channels);
  images.names = images.current_pngs;
  for (const auto& n : images.base_pngs) {
    if (std::find(images.names.begin(), images.names.end(), n) == images.names.end()) {
      images.names.push_back(n);
    }
  }
  return images;
}

void side_by_side(std::ostream& out, const CaseChange& c, const ChangeImages& images) {
  out << fmt::format("<h3 id=\"detail-{}\" class=\"k-{}\">{} — {}: {} → {}</h3>\n",
                     xml_escaped(c.name), to_string(c.kind), xml_escaped(c.name), to_string(c.kind),
                     status_text(c.base), status_text(c.current));
  if (!c.message.empty()) out << "<p class=\"message\">" << xml_escaped(c.message) << "</p>\n";
  const auto& [base, current, base_pngs, current_pngs, names] = images;
  out << "<table class=\"images\">\n<tr><th>file</th><th>base</th><th>current</th></tr>\n";
  auto cell = [&](const fs::path& dir, const std::vector<std::string>& have,
                  const std::string& name) {
    if (std::find(have.begin(), have.end(), name) == have.end()) {
      out << "<td class=\"image\">(none)</td>";
    } else {
      out << "<td class=\"image\">" << img_tag(dir / name, name) << "</td>";
    }
  };
  for (const auto& name : names) {
    out << "<tr><td><code>" << xml_escaped(name) << "</code></td>";
    cell(base, base_pngs, name);
    cell(current, current_pngs, name);
    out << "</tr>\n";
  }
  out << "</table>\n";
}

}  // namespace

void write_run_html(const std::filesystem::path& file, const RunResults& results,
                    const std::filesystem::path& run_dir) {
  std::ostringstream out;
  begin_page(out, "glrefcheck — " + results.run.driver + " (" + results.run.backend + ")",
             "report");
  run_summary(out, results);
  case_table(out, results.cases);
  std::vector<const CaseResult*> failing;
  for (const auto& r : results.cases) {
    if (is_failing(r)) failing.push_back(&r);
  }
  if (!failing.empty()) {
    out << "<h2>Failing cases</h2>\n";
    for (const CaseResult* r : failing)
      case_detail(out, *r, run_dir);
  }
  end_page(out);
  write_file(file, out.str());
}

void write_comparison_html(const std::filesystem::path& file, const RunComparison& comparison,
                           const std::filesystem::path& base_dir,
                           const std::filesystem::path& current_dir) {
  const RunComparison& c = comparison;
  std::ostringstream out;
  begin_page(out,
             "glrefcheck compare — " + c.base.driver + " (" + c.base.backend + ") → " +
                 c.current.driver + " (" + c.current.backend + ")",
             "compare");
  comparison_header(out, c);
  out << "<p class=\"counts\">";
  for (auto k : kKindOrder) {
    out << fmt::format("<span class=\"k-{0}\">{0}: {1}</span>", to_string(k), c.count(k));
  }
  out << fmt::format("<span>total: {}</span></p>\n", c.cases.size());

  out << "<h2>Changed cases</h2>\n";
  // Only cases with pictures get a section (and a link to it); `run` draws heatmaps for failing
  // cases, so a precision change between two passing runs usually has none.
  std::vector<ChangeImages> images(c.cases.size());
  std::vector<bool> has_images(c.cases.size(), false);
  for (size_t i = 0; i < c.cases.size(); ++i) {
    if (!shows_images(c.cases[i].kind)) continue;
    images[i] = change_images(c.cases[i], base_dir, current_dir);
    has_images[i] = !images[i].names.empty();
  }

  const bool any = std::any_of(c.cases.begin(), c.cases.end(), [](const CaseChange& x) {
    return x.kind != CaseChange::Kind::unchanged;
  });
  if (!any) {
    out << "<p>Every case is unchanged.</p>\n";
  } else {
    out << "<table class=\"cases\">\n<tr><th>case</th><th>change</th><th>base → current</th>"
           "<th>error grew (max ulp, base → current)</th><th>message</th></tr>\n";
    for (size_t i = 0; i < c.cases.size(); ++i) {
      const CaseChange& x = c.cases[i];
      if (x.kind == CaseChange::Kind::unchanged) continue;
      std::string name = xml_escaped(x.name);
      if (has_images[i]) {
        name = "<a href=\"#detail-" + fragment(x.name) + "\">" + name + "</a>";
      }
      out << fmt::format(
          "<tr id=\"case-{}\" class=\"k-{}\"><td>{}</td><td>{}</td><td>{} → {}</td>"
          "<td class=\"mono\">{}</td><td class=\"message\">{}</td></tr>\n",
          xml_escaped(x.name), to_string(x.kind), name, to_string(x.kind), status_text(x.base),
          status_text(x.current), grown_channels(x), xml_escaped(x.message));
    }
    out << "</table>\n";
  }

  if (std::find(has_images.begin(), has_images.end(), true) != has_images.end()) {
    out << "<h2>Heatmaps: base | current</h2>\n";
    for (size_t i = 0; i < c.cases.size(); ++i) {
      if (has_images[i]) side_by_side(out, c.cases[i], images[i]);
    }
  }
  std::string without;
  for (size_t i = 0; i < c.cases.size(); ++i) {
    if (!shows_images(c.cases[i].kind) || has_images[i]) continue;
    without += (without.empty() ? "" : ", ") + xml_escaped(c.cases[i].name);
  }
  if (!without.empty()) {
    out << "<p>No heatmaps in either run's <code>cases/</code> folder for: " << without
        << ".</p>\n";
  }
  end_page(out);
  write_file(file, out.str());
}

}  // namespace glrc::report
