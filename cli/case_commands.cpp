#include "cli/case_commands.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <limits>

#include "check/check.hpp"
#include "cli/identify.hpp"
#include "cli/output_dir.hpp"
#include "cli/run_support.hpp"
#include "driver_models/driver_models.hpp"
#include "ref/reference.hpp"
#include "report/format.hpp"
#include "report/report.hpp"
#include "report/stamp.hpp"

namespace glrc::cli {

int cmd_diff(const Options& o) {
  const std::vector<Case> cases = load_cases(o);
  if (cases.size() != 1)
    throw InputError("diff: expected exactly one case, got " + std::to_string(cases.size()) +
                     " (use --filter or name one file)");
  const Case& c = cases[0];
  const OutputFolder folder = output_folder(o.out);
  const std::filesystem::path& out = folder.path;
  auto renderer = open_renderer(o);
  const ModelChoice model = choose_model(o, *renderer);
  // A file of the user's by an image's name is refused before anything changes. The last diff's
  // images go first, none of another case staying beside this one's; only once GL is up, so
  // that a diff whose driver cannot start leaves them.
  clear_diff_images(out, report::diff_image_names(c));
  check::CheckOptions judged = check_options(o);
  judged.model = model.model;
  // diff is for looking at a case's heatmaps: its frames are kept whole, however large.
  judged.whole_frame_bytes = std::numeric_limits<size_t>::max();
  const RunInfo info = run_info(o, renderer->info(), model);
  const check::Checked checked = check::check_with_frames(c, *renderer, judged);
  const CaseResult& r = checked.result;
  fmt::print("{}: {}\nGL: {} | {} | GL_SUBPIXEL_BITS {} | model {} from {} | tolerance {}\n\n",
             c.name, c.description, info.gl_renderer, info.gl_version, info.subpixel_bits,
             info.model, info.model_source, info.tolerance);
  for (const std::string& w : info.gl_warnings)
    fmt::print("warning: {}\n", w);
  if (!info.gl_warnings.empty()) fmt::print("\n");
  fmt::print("{}\n", report::case_line(r));
  if (r.status == Status::error) return 1;
  fmt::print("\n{}\n", report::stats_table(r));
  // Coverage first: a pixel covered by the wrong triangle has no value error to show.
  if (const std::string table =
          report::coverage_failures_table(r, checked.expected.frame, checked.gl, 20);
      !table.empty())
    fmt::print("{}\n", table);
  if (const std::string table = report::worst_pixels_table(r, 10); !table.empty())
    fmt::print("{}\n", table);
  // Each name is recorded before its file is written: a diff stopped halfway leaves none
  // unlisted.
  std::vector<std::pair<std::filesystem::path, std::string>> listed;
  const auto files = report::write_diff_images(out, c, checked.expected, checked.gl, r,
                                               [&](const std::filesystem::path& file) {
                                                 listed.emplace_back(file, "");
                                                 record_diff_images(out, listed);
                                               });
  // Each image's content as written: the next diff deletes it only while it is unchanged.
  for (auto& [file, digest] : listed)
    digest = report::content_digest(read_file(file));
  record_diff_images(out, listed);
  fmt::print("wrote {} to {}/\n", report::count_text(files.size(), "image", "images"), o.out);
  return fails_run(r.status) ? 1 : 0;
}

// No GL here, so nothing to identify: --model identified (the default) and ideal both give the
// fixed model of --subpixel-bits, --planes and --tie-break, which tests/digests.txt holds.
int cmd_digest(const Options& o) {
  const auto driver = driver_models::driver_from_string(o.model.name);
  for (const Case& c : load_cases(o))
    fmt::print("{}  {}\n",
               ref::digest(driver ? driver_models::render(c, *driver)
                                  : ref::render_frame(c, o.model.reference_model(), o.threads)),
               c.name);
  return 0;
}

int cmd_list(const Options& o) {
  const std::vector<Case> cases = load_cases(o);
  size_t width = 0;
  for (const Case& c : cases)
    width = std::max(width, c.name.size());
  for (const Case& c : cases)
    fmt::print("{:<{}}  {}\n", c.name, width, c.description);
  return 0;
}

}  // namespace glrc::cli
