#include "cli/fuzz.hpp"

#include <signal.h>

#include <fmt/core.h>
#include <charconv>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <set>

#include "campaign/campaign.hpp"
#include "casefile/write.hpp"
#include "cli/interrupts.hpp"
#include "cli/mesa_prefix.hpp"
#include "cli/output_dir.hpp"
#include "cli/run_support.hpp"
#include "cli/validators.hpp"
#include "cli/workers/process.hpp"
#include "cli/workers/workers.hpp"
#include "core/text.hpp"
#include "report/format.hpp"
#include "report/html.hpp"
#include "report/json_types.hpp"
#include "report/report.hpp"
#include "report/stamp.hpp"

namespace glrc::cli {
namespace {

std::vector<const campaign::Generator*> chosen_generators(const FuzzOptions& f) {
  std::vector<const campaign::Generator*> chosen;
  if (f.generators.empty())
    for (const campaign::Generator& g : campaign::generators())
      chosen.push_back(&g);
  for (const std::string& name : f.generators) {
    const campaign::Generator* g = campaign::find_generator(name);
    if (!g) {
      std::string names;
      for (const campaign::Generator& h : campaign::generators())
        names += (names.empty() ? "" : ", ") + std::string(h.name);
      throw InputError("--generator: expected one of " + names + ", got \"" + printable(name, 80) +
                       "\"");
    }
    chosen.push_back(g);
  }
  return chosen;
}

uint64_t whole(std::string_view text, const std::string& what) {
  uint64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) throw InputError(what);
  return v;
}

std::pair<uint64_t, uint64_t> parse_replay(const std::string& text) {
  const std::string what =
      "--replay: expected SEED:INDEX, two whole numbers (as a campaign "
      "prints them), got \"" +
      printable(text, 80) + "\"";
  const size_t colon = text.find(':');
  if (colon == std::string::npos) throw InputError(what);
  const uint64_t seed = whole(std::string_view(text).substr(0, colon), what);
  const uint64_t index = whole(std::string_view(text).substr(colon + 1), what);
  // The campaign checks cases 0 .. index: index + 1 of them, which must not wrap to none.
  if (index == std::numeric_limits<uint64_t>::max())
    throw InputError("--replay: expected an INDEX below 18446744073709551615, got \"" +
                     printable(text, 80) + "\"");
  return {seed, index};
}

// A case file with its stamp in "written_by" (report/stamp.hpp; the case format ignores the
// field): --emit replaces only a file fuzz wrote that nobody edited since.
void write_case_file(const std::filesystem::path& file, const Case& c) {
  report::write_file_atomically(file, report::stamped_json("fuzz", casefile::to_case_file(c)));
}

}  // namespace

std::set<std::string> listed_failure_files(const std::filesystem::path& out) {
  std::set<std::string> names;
  std::error_code ec;
  if (std::filesystem::is_regular_file(
          std::filesystem::symlink_status(out / kFailuresWritten, ec))) {
    std::ifstream written(out / kFailuresWritten);
    for (std::string name; std::getline(written, name);)
      // A file's name alone: a line naming a path elsewhere lists nothing.
      if (!name.empty() && std::filesystem::path(name).filename() == name) names.insert(name);
  }
  if (!std::filesystem::is_regular_file(out / "results.json", ec)) return names;
  try {
    std::ifstream in(out / "results.json", std::ios::binary);
    const nlohmann::json doc = nlohmann::json::parse(in);
    if (!campaign::is_campaign_json(doc)) return names;
    for (const nlohmann::json& f : doc.at("failures"))
      names.insert(std::filesystem::path(f.at("file").get<std::string>()).filename().string());
  } catch (const std::exception&) {
    // Unreadable: it lists nothing, and whatever is in failures/ is refused.
  }
  return names;
}

void write_campaign_files(const std::filesystem::path& out, const nlohmann::json& doc) {
  // Stamped, so that merge notices a shard's results edited by hand (a failure taken out).
  report::write_file_atomically(out / "results.json",
                                report::stamped_json("fuzz", doc.dump(2) + "\n"));
  // deqp-runner's format, one line per distinct failure (its minimal case's name).
  std::string csv;
  for (const nlohmann::json& f : doc["failures"]) {
    std::string name = f.value("file", "");
    name = std::filesystem::path(name).stem().string();
    const double seconds = f.contains("result") ? f["result"].value("seconds", 0.0) : 0.0;
    csv += fmt::format("{},{},{:.3f}\n", name, f.value("known", false) ? "ExpectedFail" : "Fail",
                       seconds);
  }
  report::write_file_atomically(out / "results.csv", csv);
  // results.json lists the minimal cases now.
  std::error_code ec;
  std::filesystem::remove(out / kFailuresWritten, ec);
}

CLI::App* add_fuzz_command(CLI::App& app, FuzzOptions& f) {
  auto* cmd = app.add_subcommand(
      "fuzz",
      "random campaigns: generated cases checked on GL, each distinct failure shrunk to a "
      "minimal case in <out>/failures/");
  cmd->add_option("--seed", f.seed, "the campaign's seed (default: a fresh one, printed)")
      ->check(whole_u64());
  cmd->add_option("--count", f.count, "check this many cases (default 200 without --time)")
      ->check(whole_u64(1));
  cmd->add_option("--time", f.seconds, "check cases for this many seconds")
      ->check(finite_range(0.001, 1e7));
  std::string generators_help = "the generators to draw cases from (default: all):";
  for (const campaign::Generator& g : campaign::generators())
    generators_help += fmt::format(" {}: {};", g.name, g.aims_at);
  cmd->add_option("--generator", f.generators, generators_help);
  cmd->add_option("--replay", f.replay,
                  "SEED:INDEX: only that case of the campaign (with the campaign's --generator "
                  "list); with --emit, write it as a case file instead of checking it");
  cmd->add_option("--emit", f.emit, "with --replay: the case file to write");
  cmd->add_option("--shrink-time", f.shrink_seconds,
                  "seconds shrinking one failure may take (default 60)")
      ->check(finite_range(0, 1e7));
  cmd->add_flag("--no-shrink", f.no_shrink, "keep each failure's first case as found");
  cmd->add_option(
      "--baseline", f.baseline,
      "known campaign failures, `<failure>,Fail` lines (non_finite_noperspective,Fail): "
      "reported as known, they do not fail the campaign");
  return cmd;
}

namespace {

// The campaign asked for: generators, seed and count or time (or the one case of --replay),
// shard, shrinking. InputError on options that do not go together.
campaign::CampaignOptions plan_campaign(const Options& o, const FuzzOptions& f) {
  judging(o);  // options that cannot judge a case: refused before any work
  campaign::CampaignOptions co;
  co.generators = chosen_generators(f);
  if (!f.emit.empty() && !f.replay)
    throw InputError("--emit: expected --replay SEED:INDEX with it (the case to write)");
  if (!f.emit.empty() && f.out_given)
    throw InputError("--out: expected no --out with --emit (--emit names the one file written)");
  if (f.replay && (f.seed || f.count || f.seconds || o.fraction != 1 || o.fraction_start != 1))
    throw InputError(
        "--replay: expected no --seed, --count, --time, --fraction or --fraction-start with it "
        "(SEED:INDEX names the case)");
  if (o.fraction < 1 || o.fraction_start < 1 || o.fraction_start > o.fraction)
    throw InputError(
        fmt::format("--fraction {} --fraction-start {}: expected 1 <= fraction-start <= fraction",
                    o.fraction, o.fraction_start));
  if (f.replay) {
    const auto [seed, index] = parse_replay(*f.replay);
    co.seed = seed, co.only_index = index, co.count = index + 1;
  } else {
    co.seed = f.seed ? *f.seed : std::random_device{}() * 0x100000000ull + std::random_device{}();
    co.count = f.count, co.seconds = f.seconds;
    if (!co.count && !co.seconds) co.count = 200;
  }
  co.fraction = o.fraction, co.fraction_start = o.fraction_start;
  co.shrink = !f.no_shrink;
  co.shrinking.seconds = f.shrink_seconds;
  return co;
}

// --replay SEED:INDEX --emit FILE: the case written as a case file, not checked.
int emit_replayed(const std::string& file, const campaign::CampaignOptions& co) {
  const Case c = campaign::generate(co.generators, co.seed, *co.only_index);
  check_replaceable(file, "--emit", "fuzz");
  write_case_file(file, c);
  fmt::print("wrote {}: {}, {} triangles, {} varyings\n", file, c.name, c.triangles.size(),
             c.varyings.size());
  return 0;
}

// What judges the campaign besides GL and the model: its known failures (--baseline) and the
// verdict inputs merge compares between shards.
struct CampaignJudging {
  Baseline baseline;
  std::map<std::string, std::string> judged_by;
  bool known(const campaign::Failure& failure) const {
    const std::string file = campaign::failure_file_name(failure);
    return baseline.expected.count(file.substr(0, file.size() - 5)) > 0;
  }
};

CampaignJudging read_campaign_judging(const Options& o, const FuzzOptions& f) {
  Options for_baseline;
  for_baseline.baseline = f.baseline;
  CampaignJudging j{load_baseline(for_baseline), {}};
  // A campaign's known failure is `<failure>,Fail`: another status, or a name no failure has (the
  // signature as printed, non_finite/noperspective), would be a line that silently matches
  // nothing, or matches what it should not.
  for (const auto& [name, status] : j.baseline.expected) {
    if (status != "Fail")
      throw InputError(fmt::format(
          "--baseline {}: {}: expected the status Fail (a campaign failure is listed as "
          "`<failure>,Fail`), got {}",
          printable(f.baseline, 200), printable(name, 80), printable(status, 40)));
    if (const auto problem = campaign::failure_name_problem(name))
      throw InputError(fmt::format("--baseline {}: expected {}, got \"{}\"",
                                   printable(f.baseline, 200), *problem, printable(name, 80)));
  }
  Options judged = o;
  judged.baseline = f.baseline, judged.flakes.clear(), judged.skips.clear();
  j.judged_by = verdict_inputs(judged);
  return j;
}

// The campaign itself, on worker processes: each failure found printed, its minimal case
// written into failures/ and checked once more for its heatmaps, and the campaign's files
// written at the end.
class FuzzCampaign {
 public:
  FuzzCampaign(Options& o, campaign::CampaignOptions& co, const CampaignJudging& judging,
               const std::optional<MesaPrefix>& prefix, const std::filesystem::path& out,
               EarlierOutputs& earlier, int interrupt_fd)
      : o_(o), co_(co), judging_(judging), prefix_(prefix), out_(out), earlier_(earlier) {
    s_ = worker_settings(o_, out_, interrupt_fd, prefix_);
    // Heatmaps for the minimal cases only (checked once more when shrunk), for report.html.
    s_.images = [this](const Case& c) { return with_images_.count(c.name) > 0; };
    co_.batch = size_t(std::max(4 * s_.jobs, 8));
    co_.shrinking.batch = size_t(std::max(s_.jobs, 1));
    info_.backend = gl::to_string(o_.gl.backend), info_.driver = o_.gl.driver, info_.jobs = s_.jobs;
    info_.mesa_prefix = o_.gl.mesa;
    info_.verdict_inputs = judging_.judged_by;
  }

  int execute() {
    WorkerSession session(
        o_, s_, [this](const gl::GlInfo& gl, const ModelChoice& model) { on_start(gl, model); });
    session_ = &session;
    const campaign::Judge judge = [&](const std::vector<Case>& cases) {
      std::vector<const Case*> pointers;
      for (const Case& c : cases)
        pointers.push_back(&c);
      return session.check(pointers);
    };
    std::filesystem::create_directories(out_ / "failures");
    campaign::CampaignResult result = campaign::run_campaign(co_, judge, progress());
    clear_line();
    return write(result);
  }

 private:
  void clear_line() const {
    if (terminal_) fmt::print(stderr, "\r\033[K"), std::fflush(stderr);
  }

  void on_start(const gl::GlInfo& gl, const ModelChoice& model) {
    if (prefix_ && !from_prefix(*prefix_, gl.library))
      throw InputError("--mesa " + o_.gl.mesa + ": GL came from " +
                       (gl.library.empty() ? "an unknown library" : gl.library) +
                       ", not from the prefix (GL_VERSION " + gl.version + ")");
    const RunInfo run = run_info(o_, gl, model);
    info_.gl_vendor = run.gl_vendor, info_.gl_renderer = run.gl_renderer;
    info_.gl_version = run.gl_version, info_.gl_library = run.gl_library;
    info_.model = run.model, info_.model_source = run.model_source;
    info_.tolerance = run.tolerance, info_.subpixel_bits = run.subpixel_bits;
    info_.gl_warnings = run.gl_warnings;
    gl_started_ = true;
    earlier_.keep_new();
    print_start();
  }

  void print_start() const {
    std::string generators;
    for (const campaign::Generator* g : co_.generators)
      generators += (generators.empty() ? "" : ",") + std::string(g->name);
    fmt::print(
        "glrefcheck fuzz: seed {}, generators {}, {} on {} ({}), GL {} | model {} from {} "
        "| tolerance {} | {} worker{}\n",
        co_.seed, generators,
        co_.only_index             ? fmt::format("case {}", *co_.only_index)
        : co_.count && co_.seconds ? fmt::format("{} cases or {} s", *co_.count, *co_.seconds)
        : co_.count                ? fmt::format("{} cases", *co_.count)
                                   : fmt::format("{} s", *co_.seconds),
        info_.gl_renderer, info_.backend, info_.gl_version, info_.model, info_.model_source,
        info_.tolerance, s_.jobs, s_.jobs == 1 ? "" : "s");
    for (const std::string& w : info_.gl_warnings)
      fmt::print("warning: {}\n", w);
    std::fflush(stdout);
  }

  campaign::CampaignProgress progress() {
    campaign::CampaignProgress progress;
    progress.stop = [] { return caught_signal() != 0; };
    progress.batch_done = [this](const campaign::CampaignStats& st, size_t distinct) {
      if (!terminal_) return;
      fmt::print(stderr,
                 "\r\033[K{} cases, {} triangles, {} pixels | {} failing, {} distinct | {:.0f} "
                 "triangles/s | {:.0f} s",
                 st.cases, st.triangles, st.pixels, st.failing_cases, distinct,
                 st.triangles_per_second(), st.seconds);
      std::fflush(stderr);
    };
    progress.found = [this](const campaign::FoundFailure& nf) {
      clear_line();
      fmt::print("{} {} in {}_{}_{}: {}\n",
                 judging_.known(nf.failure) ? "known failure" : "new failure",
                 nf.failure.signature(), nf.generator, nf.seed, nf.index, nf.first_description);
      std::fflush(stdout);
    };
    progress.shrunk = [this](const campaign::FoundFailure& nf) { shrunk(nf); };
    return progress;
  }

  void shrunk(const campaign::FoundFailure& nf) {
    const auto file = out_ / "failures" / campaign::failure_file_name(nf.failure);
    // Named as this campaign's before it exists: killed outright, the campaign leaves no
    // results.json, and the next one there must know the file for its own.
    {
      std::ofstream written(out_ / kFailuresWritten,
                            failures_written_ ? std::ios::app : std::ios::trunc);
      written << file.filename().string() << '\n' << std::flush;
      if (!written) throw std::runtime_error("cannot write " + (out_ / kFailuresWritten).string());
      failures_written_ = true;
    }
    write_case_file(file, nf.minimal);
    // Its heatmaps, in <out>/cases/<name>/ as `run` writes a failing case's.
    with_images_.insert(nf.minimal.name);
    CaseResult again = session_->check({&nf.minimal}).front();
    report::apply(judging_.baseline, again);
    minimal_results_.push_back(std::move(again));
    clear_line();
    fmt::print(
        "  {}: {} triangle{}, {} varying{} ({:.1f} s, {} steps, {} checks), {:.1f} s into the "
        "campaign: {}\n",
        campaign::to_text(nf.shrink_end), nf.minimal.triangles.size(),
        nf.minimal.triangles.size() == 1 ? "" : "s", nf.minimal.varyings.size(),
        nf.minimal.varyings.size() == 1 ? "" : "s", nf.shrink_seconds, nf.shrink_steps,
        nf.shrink_checks, nf.found_after + nf.shrink_seconds, shown_path(file.string()));
    std::fflush(stdout);
  }

  int write(campaign::CampaignResult& result) {
    // Stopped before GL started: nothing was checked, and the folder's earlier campaign comes
    // back as it was (`earlier_`, as it goes) rather than a campaign of no cases over it.
    if (!gl_started_ && result.stats.interrupted && caught_signal()) {
      fmt::print("interrupted by {} before GL started: {}\n", signal_name(caught_signal()),
                 earlier_.left_as_it_was(o_.out));
      return 128 + caught_signal();
    }
    size_t new_failures = 0;
    for (campaign::FoundFailure& nf : result.failures) {
      nf.known = judging_.known(nf.failure);
      new_failures += !nf.known;
    }
    // A campaign stopped by a signal is a run stopped by one: merge refuses it.
    info_.interrupted = result.stats.interrupted;
    info_.total_cases = result.stats.cases;
    info_.seconds = result.stats.seconds;
    nlohmann::json run;
    glrc::to_json(run, info_);
    nlohmann::json doc = campaign::campaign_json(result, run);
    // Each minimal case's check as results.json has a case's, for `merge` and `report`.
    for (size_t i = 0; i < doc["failures"].size() && i < minimal_results_.size(); ++i)
      doc["failures"][i]["result"] =
          nlohmann::json::parse(report::case_result_json(minimal_results_[i]));
    write_campaign_files(out_, doc);
    // The page of the minimal failures: each one's statistics and heatmaps.
    RunInfo page = info_;
    page.total_cases = minimal_results_.size();
    report::write_run_html(out_ / "report.html", {page, minimal_results_}, out_);
    earlier_.keep_new();
    print_summary(result, new_failures);
    if (result.stats.interrupted) return 128 + (caught_signal() ? caught_signal() : SIGINT);
    return new_failures == 0 ? 0 : 1;
  }

  void print_summary(const campaign::CampaignResult& result, size_t new_failures) const {
    const campaign::CampaignStats& st = result.stats;
    fmt::print(
        "\n{} cases, {} triangles, {} pixels checked in {:.1f} s ({:.0f} triangles/s); {} "
        "failing, {} distinct failure{} ({} new){}\n",
        st.cases, st.triangles, st.pixels, st.seconds, st.triangles_per_second(), st.failing_cases,
        result.failures.size(), result.failures.size() == 1 ? "" : "s", new_failures,
        st.skipped ? fmt::format("; {} skipped (beyond GL's specified range)", st.skipped) : "");
    if (st.interrupted)
      fmt::print("interrupted by {} after {}: its results hold the cases checked\n",
                 signal_name(caught_signal()), report::count_text(st.cases, "case", "cases"));
    fmt::print("results in {}\n", shown_path(out_.string()));
  }

  Options& o_;
  campaign::CampaignOptions& co_;
  const CampaignJudging& judging_;
  const std::optional<MesaPrefix>& prefix_;
  const std::filesystem::path& out_;
  EarlierOutputs& earlier_;
  WorkerSettings s_;
  RunInfo info_;
  WorkerSession* session_ = nullptr;  // while execute() runs
  std::set<std::string> with_images_;
  std::vector<CaseResult> minimal_results_;
  bool gl_started_ = false;
  bool failures_written_ = false;  // kFailuresWritten holds this campaign's names, not another's
  const bool terminal_ = isatty(STDERR_FILENO) && !std::getenv("CI");
};

}  // namespace

// Plan (the campaign's options), read what judges it, claim the folder, then run and write.
int cmd_fuzz(const Options& given, const FuzzOptions& f) {
  Options o = given;
  campaign::CampaignOptions co = plan_campaign(o, f);
  if (!f.emit.empty()) return emit_replayed(f.emit, co);
  const CampaignJudging judging = read_campaign_judging(o, f);
  std::optional<MesaPrefix> prefix;
  if (!o.gl.mesa.empty()) prefix = find_mesa_prefix(o.gl.mesa, gl::to_string(o.gl.backend));
  const int interrupt_fd = catch_interrupts();
  const OutputFolder folder = output_folder(o.out);
  if (!f.baseline.empty())
    check_inputs_outside(folder.path, {"failures"}, {{"this campaign's --baseline", f.baseline}},
                         "--out " + o.out);
  // The earlier campaign's outputs come back if this one never gets GL; its minimal cases are
  // the campaign's while unedited (set_aside_outputs refuses one a person changed or added).
  EarlierOutputs earlier = set_aside_outputs(folder.path, {"failures"});
  return FuzzCampaign(o, co, judging, prefix, folder.path, earlier, interrupt_fd).execute();
}

}  // namespace glrc::cli
