// The HTML reports, opened in headless Chromium: the DOM it builds is what a reader sees, and its
// load script tells whether the embedded PNGs really decode.
#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "report/html.hpp"
#include "tests/report/test_helpers.hpp"

namespace glrc::report::test {
namespace {

namespace fs = std::filesystem;

// The first of the usual Chromium names on PATH, or empty.
std::string find_chromium() {
  const char* path = std::getenv("PATH");
  if (!path) return {};
  for (const char* name : {"chromium", "chromium-browser", "google-chrome"}) {
    std::stringstream dirs(path);
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
      if (dir.empty()) continue;
      const fs::path candidate = fs::path(dir) / name;
      if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    }
  }
  return {};
}

// Single quotes keep the shell from reading anything in a path.
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s)
    out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

void write_png(const fs::path& file) {
  fs::create_directories(file.parent_path());
  std::vector<unsigned char> pixels(4 * 4 * 3);
  for (size_t i = 0; i < pixels.size(); ++i)
    pixels[i] = static_cast<unsigned char>(i * 5);
  auto out = OIIO::ImageOutput::create(file.string());
  ASSERT_TRUE(out) << OIIO::geterror();
  ASSERT_TRUE(out->open(file.string(), OIIO::ImageSpec(4, 4, 3, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
  ASSERT_TRUE(out->close());
}

// The text from `from` up to the end of its table row.
std::string row_of(const std::string& dom, const std::string& from) {
  const auto begin = dom.find(from);
  if (begin == std::string::npos) return {};
  return dom.substr(begin, dom.find("</tr>", begin) - begin);
}

class HtmlTest : public ReportTest {
 protected:
  // The DOM after load (the virtual time budget lets the load script run first). Chromium's
  // stderr is noise (GPU, D-Bus, its launcher script) and is dropped.
  std::string dump_dom(const fs::path& html) {
    const std::string chromium = find_chromium();
    const fs::path profile = dir_ / "chromium-profile";
    fs::create_directories(profile);
    const std::string command =
        "HOME=" + quoted(profile.string()) + " timeout 120 " + quoted(chromium) +
        " --headless --no-sandbox --disable-gpu --no-first-run --user-data-dir=" +
        quoted(profile.string()) + " --virtual-time-budget=2000 --dump-dom " +
        quoted("file://" + fs::absolute(html).string()) + " 2>/dev/null";
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) throw std::runtime_error("cannot run " + command);
    std::string dom;
    char buffer[65536];
    for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
      dom.append(buffer, n);
    const int status = ::pclose(pipe);
    EXPECT_EQ(status, 0) << command;
    return dom;
  }

  void SetUp() override {
    ReportTest::SetUp();
    if (find_chromium().empty()) {
      GTEST_SKIP() << "no chromium, chromium-browser or google-chrome on PATH: the HTML report "
                      "is not rendered (scripts/install-deps.sh installs chromium)";
    }
  }
};

RunResults sample_run() {
  RunResults results;
  results.run = run_info();
  results.run.mesa_prefix = "/opt/mesa-main";
  CaseResult pass = passing_case();
  pass.outcome = Status::pass;
  CaseResult fail = nan_case();
  fail.outcome = Status::fail;
  CaseResult odd = with_status(Status::crash, "odd<&>name", "died in <b>draw</b> & \"quit\"");
  odd.outcome = Status::crash;
  results.cases = {pass, fail, odd};
  return results;
}

TEST_F(HtmlTest, RunReportRendersWithEmbeddedImages) {
  const RunResults results = sample_run();
  const fs::path run_dir = dir_ / "run";
  write_png(run_dir / "cases" / "nan_varying" / "color.y_error.png");
  const fs::path html = run_dir / "report.html";
  write_run_html(html, results, run_dir);

  const std::string text = read_text(html);
  EXPECT_NE(text.find("data:image/png;base64,"), std::string::npos);
  EXPECT_EQ(text.find("http://"), std::string::npos) << "the report must be self-contained";
  EXPECT_EQ(text.find("https://"), std::string::npos) << "the report must be self-contained";

  const std::string dom = dump_dom(html);
  ASSERT_NE(dom.find("</html>"), std::string::npos) << "no DOM from Chromium:\n" << dom;
  EXPECT_NE(dom.find("glrefcheck — llvmpipe (osmesa)"), std::string::npos);
  EXPECT_NE(dom.find("4.5 (Compatibility Profile) Mesa 22.3.6"), std::string::npos);
  EXPECT_NE(dom.find("llvmpipe (LLVM 15.0.6, 256 bits)"), std::string::npos);
  EXPECT_NE(dom.find("/opt/mesa-main"), std::string::npos);
  EXPECT_NE(dom.find(">Pass: 1<"), std::string::npos);
  EXPECT_NE(dom.find(">Fail: 1<"), std::string::npos);
  EXPECT_NE(dom.find(">Crash: 1<"), std::string::npos);
  EXPECT_NE(dom.find(">total: 3<"), std::string::npos);

  const std::string pass_row = row_of(dom, "id=\"case-face_on\"");
  ASSERT_FALSE(pass_row.empty()) << dom;
  EXPECT_NE(pass_row.find(">Pass<"), std::string::npos) << pass_row;
  EXPECT_NE(pass_row.find(">3.1<"), std::string::npos) << pass_row;
  const std::string fail_row = row_of(dom, "id=\"case-nan_varying\"");
  ASSERT_FALSE(fail_row.empty()) << dom;
  EXPECT_NE(fail_row.find(">Fail<"), std::string::npos) << fail_row;
  EXPECT_NE(fail_row.find(">inf<"), std::string::npos) << fail_row;

  // The DOM dump escapes text again, so markup in a name or message shows up escaped, never as
  // elements.
  EXPECT_NE(dom.find(">odd&lt;&amp;&gt;name<"), std::string::npos) << dom;
  EXPECT_NE(dom.find("died in &lt;b&gt;draw&lt;/b&gt; &amp; \"quit\""), std::string::npos);
  EXPECT_EQ(dom.find("<b>"), std::string::npos);
  // The crashed case has no heatmap folder, and says so.
  EXPECT_NE(dom.find("No heatmaps"), std::string::npos);
  EXPECT_NE(dom.find(">color.y_error.png<"), std::string::npos);

  EXPECT_NE(dom.find("data-images-loaded=\"1\""), std::string::npos) << dom;
  EXPECT_NE(dom.find("data-images-total=\"1\""), std::string::npos) << dom;
}

TEST_F(HtmlTest, ComparisonReportShowsBothRunsSideBySide) {
  RunComparison c;
  c.base = run_info();
  c.current = run_info();
  c.current.gl_version = "4.6 (Compatibility Profile) Mesa 24.1.0-devel";
  c.current.mesa_prefix = "/opt/mesa-main";

  CaseChange regressed;
  regressed.name = "worse<&>";
  regressed.kind = CaseChange::Kind::regression;
  regressed.base = Status::pass;
  regressed.current = Status::fail;
  regressed.message = "color.x: 3 over tolerance";
  ChannelChange ch;
  ch.channel = "color.x";
  ch.base_max_ulps = 3.1;
  ch.current_max_ulps = 120;
  ch.max_grew = true;
  regressed.channels = {ch};
  CaseChange fixed;
  fixed.name = "better";
  fixed.kind = CaseChange::Kind::fix;
  fixed.base = Status::fail;
  fixed.current = Status::pass;
  CaseChange same;
  same.name = "same_as_ever";
  same.base = same.current = Status::pass;
  CaseChange added;
  added.name = "brand_new";
  added.kind = CaseChange::Kind::added;
  added.current = Status::pass;
  CaseChange drifted;
  drifted.name = "drifted";
  drifted.kind = CaseChange::Kind::precision;
  drifted.base = drifted.current = Status::pass;
  c.cases = {regressed, fixed, same, added, drifted};

  const fs::path base_dir = dir_ / "base", current_dir = dir_ / "current";
  write_png(base_dir / "cases" / "worse<&>" / "color.x_error.png");
  write_png(current_dir / "cases" / "worse<&>" / "color.x_error.png");
  const fs::path html = dir_ / "compare.html";
  write_comparison_html(html, c, base_dir, current_dir);

  const std::string dom = dump_dom(html);
  ASSERT_NE(dom.find("</html>"), std::string::npos) << "no DOM from Chromium:\n" << dom;
  EXPECT_NE(dom.find("4.5 (Compatibility Profile) Mesa 22.3.6"), std::string::npos);
  EXPECT_NE(dom.find("4.6 (Compatibility Profile) Mesa 24.1.0-devel"), std::string::npos);
  EXPECT_NE(dom.find(">regression: 1<"), std::string::npos);
  EXPECT_NE(dom.find(">fix: 1<"), std::string::npos);
  EXPECT_NE(dom.find(">added: 1<"), std::string::npos);
  EXPECT_NE(dom.find(">unchanged: 1<"), std::string::npos);

  const std::string row = row_of(dom, "id=\"case-worse");
  ASSERT_FALSE(row.empty()) << dom;
  EXPECT_NE(row.find(">worse&lt;&amp;&gt;<"), std::string::npos) << row;
  EXPECT_NE(row.find(">regression<"), std::string::npos) << row;
  EXPECT_NE(row.find("Pass → Fail"), std::string::npos) << row;
  EXPECT_NE(row.find("color.x: 3.1 → 120 ulp"), std::string::npos) << row;
  EXPECT_FALSE(row_of(dom, "id=\"case-better\"").empty());
  EXPECT_NE(row_of(dom, "id=\"case-brand_new\"").find("— → Pass"), std::string::npos);
  // A precision change between passing runs has no heatmaps, and is named in a sentence.
  EXPECT_NE(dom.find("No heatmaps in either run"), std::string::npos);
  EXPECT_NE(row_of(dom, "id=\"case-drifted\"").find(">precision<"), std::string::npos);
  // Unchanged cases are counted, not listed.
  EXPECT_TRUE(row_of(dom, "id=\"case-same_as_ever\"").empty());

  EXPECT_NE(dom.find("data-images-loaded=\"2\""), std::string::npos) << dom;
  EXPECT_NE(dom.find("data-images-total=\"2\""), std::string::npos) << dom;
}

// No browser needed: only the error.
TEST(HtmlReport, UnwritableFileThrows) {
  const fs::path file = "/nonexistent-glrc-folder/report.html";
  try {
    write_run_html(file, RunResults{}, "/nonexistent-glrc-folder");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              "cannot write " + file.string() + " (No such file or directory)");
  }
  EXPECT_THROW(write_comparison_html(file, RunComparison{}, "/a", "/b"), std::runtime_error);
}

}  // namespace
}  // namespace glrc::report::test
