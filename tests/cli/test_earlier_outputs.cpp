// Nothing lost, second round (issue 45's hostile campaign): a run, campaign or diff whose GL never
// starts gives the folder's earlier results back; a run killed while a case's heatmaps were being
// written checks that case again on --resume; a diff stopped halfway leaves no image unlisted;
// `report` on a folder a live run holds names the run; a minimal case the user edited, or an
// output folder inside a run's, is not replaced. Real processes and real signals.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <thread>

#include "tests/support/glrefcheck_process.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

namespace fs = std::filesystem;
using glrc::test::glrefcheck;
using glrc::test::Outcome;
using glrc::test::parent_of;
using glrc::test::proxied_workers;
using glrc::test::wait_for_pid;

std::string read(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Every file under `dir` with its contents, but the lock (its holder line changes by design).
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> m;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename() != ".glrefcheck.lock")
      m[fs::relative(e.path(), dir).string()] = e.is_regular_file() ? read(e.path()) : "<folder>";
  return m;
}

// Which files differ between two snapshots, for a failure's message.
std::string differences(const std::map<std::string, std::string>& a,
                        const std::map<std::string, std::string>& b) {
  std::string text;
  for (const auto& [name, content] : a)
    if (!b.count(name) || b.at(name) != content) text += " " + name;
  for (const auto& [name, content] : b)
    if (!a.count(name)) text += " +" + name;
  return text;
}

// Runs `command` (a glrefcheck command line with its --out) with its workers held before GL
// (stalled before their hello; the first one's pid in `pidfile`), and sends `signal` to the
// runner once that worker is up: a command stopped before it had GL.
Outcome stopped_before_gl(const std::string& command, const fs::path& pidfile, int signal) {
  fs::remove(pidfile);
  Outcome o;
  std::thread run([&] {
    o = glrefcheck(command + proxied_workers("--stall-hello --pidfile '" + pidfile.string() + "'"));
  });
  const pid_t proxy = wait_for_pid(pidfile);
  EXPECT_GT(proxy, 0);
  if (proxy > 0) {
    EXPECT_EQ(kill(parent_of(proxy), signal), 0);
  }
  run.join();
  return o;
}

class EarlierOutputs : public glrc::test::TempDirTest {
 protected:
  // A run of viewport_tiny and attr_tiny into `out`, its worker held before attr_tiny (its
  // proxy's pid in `pidfile`): a live run holding its folder, until the test signals it.
  static std::thread run_held_at_attr_tiny(const fs::path& out, const fs::path& pidfile) {
    return std::thread([out, pidfile] {
      glrefcheck("run cases/viewport_tiny.json cases/attr_tiny.json --jobs 1 --out '" +
                 out.string() + "'" +
                 proxied_workers("--stall-case attr_tiny --pidfile '" + pidfile.string() + "'"));
    });
  }
};

// The hostile campaign's D1: `--driver zink` on OSMesa, or a wrapper that fails, deleted the
// folder's earlier results before the first worker said GL would not start.
TEST_F(EarlierOutputs, ARunWhoseGlNeverStartsLeavesTheEarlierResults) {
  const fs::path out = dir_ / "out";
  ASSERT_EQ(
      glrefcheck("run cases/face_on.json --jobs 1 --html --out '" + out.string() + "'").exit_code,
      0);
  const auto before = snapshot(out);
  ASSERT_TRUE(before.count("results.json"));
  for (const std::string& broken :
       {std::string("--backend osmesa --driver zink"), std::string("--worker-wrapper false")}) {
    const Outcome o = glrefcheck("run cases/face_on.json cases/attr_tiny.json --jobs 1 " + broken +
                                 " --out '" + out.string() + "'");
    EXPECT_EQ(o.exit_code, 2) << broken << o.out << o.err;
    EXPECT_EQ(snapshot(out), before) << broken << ":" << differences(before, snapshot(out));
  }
  // A campaign into it, whose GL never starts either.
  const Outcome o =
      glrefcheck("fuzz --count 4 --worker-wrapper false --out '" + out.string() + "'");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
  EXPECT_EQ(snapshot(out), before) << differences(before, snapshot(out));
  // A run that has GL replaces them as before.
  ASSERT_EQ(glrefcheck("run cases/attr_tiny.json --jobs 1 --out '" + out.string() + "'").exit_code,
            0);
  EXPECT_NE(read(out / "results.csv").find("attr_tiny,Pass"), std::string::npos);
  EXPECT_EQ(read(out / "results.csv").find("face_on"), std::string::npos);
  EXPECT_FALSE(fs::exists(out / "report.html"));
  EXPECT_FALSE(fs::exists(out / ".glrefcheck-earlier"));
}

// A run killed (kill -9) while its worker was still starting: the earlier results were set aside.
// The next glrefcheck to claim the folder for them (`report`, another run) puts them back;
// `run --resume` goes on with the run that was killed (its journal), as the user asks.
TEST_F(EarlierOutputs, ARunKilledBeforeItHadGlLeavesTheEarlierResultsToTheNext) {
  const fs::path out = dir_ / "out", pidfile = dir_ / "worker.pid";
  ASSERT_EQ(glrefcheck("run cases/face_on.json --jobs 1 --out '" + out.string() + "'").exit_code,
            0);
  const auto before = snapshot(out);
  const auto killed_before_gl = [&] {
    stopped_before_gl("run cases/attr_tiny.json --jobs 1 --out '" + out.string() + "'", pidfile,
                      SIGKILL);
    EXPECT_TRUE(fs::exists(out / ".glrefcheck-earlier"));
  };
  killed_before_gl();
  Outcome o = glrefcheck("report '" + out.string() + "'");
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;
  fs::remove(out / "report.html");
  EXPECT_EQ(snapshot(out), before) << differences(before, snapshot(out));

  killed_before_gl();
  o = glrefcheck("run --resume '" + out.string() + "'");
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;
  EXPECT_NE(o.out.find("0 of 1 case done before"), std::string::npos) << o.out;
  EXPECT_NE(read(out / "results.csv").find("attr_tiny,Pass"), std::string::npos);
  EXPECT_EQ(read(out / "results.csv").find("face_on"), std::string::npos);
  EXPECT_FALSE(fs::exists(out / ".glrefcheck-earlier"));

  // Killed halfway through setting them aside (results.json moved, the rest not yet): what is
  // not aside is still the earlier run's, and stays.
  const auto whole = snapshot(out);
  fs::create_directory(out / ".glrefcheck-earlier");
  fs::rename(out / "results.json", out / ".glrefcheck-earlier/results.json");
  const Outcome report = glrefcheck("report '" + out.string() + "'");
  EXPECT_EQ(report.exit_code, 0) << report.out << report.err;
  fs::remove(out / "report.html");
  EXPECT_EQ(snapshot(out), whole) << differences(whole, snapshot(out));
}

// The hostile campaign's W3: a runner killed after a failing case's verdict but before its
// heatmaps were written kept the verdict, and the resumed --html run had no heatmaps for it.
TEST_F(EarlierOutputs, AResumeChecksAgainACaseStoppedWritingItsHeatmaps) {
  const fs::path out = dir_ / "out", pidfile = dir_ / "worker.pid";
  const std::string cases = "cases/viewport_tiny.json cases/clip_noperspective_x_plane.json";
  std::thread run([&] {
    glrefcheck("run " + cases + " --jobs 1 --html --out '" + out.string() + "'" +
               proxied_workers("--stall-images clip_noperspective_x_plane --pidfile '" +
                               pidfile.string() + "'"));
  });
  const pid_t proxy = wait_for_pid(pidfile);
  ASSERT_GT(proxy, 0);
  // The proxy stalls once it has passed the verdict on; the runner records it a moment later.
  std::string journal;
  for (int k = 0; k < 600 && journal.find("\"heatmaps\":\"follow\"") == std::string::npos; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    journal = read(out / "journal.jsonl");
  }
  ASSERT_EQ(kill(parent_of(proxy), SIGKILL), 0);
  run.join();
  ASSERT_NE(journal.find("\"heatmaps\":\"follow\""), std::string::npos) << journal;
  const Outcome o = glrefcheck("run --resume '" + out.string() + "'");
  EXPECT_EQ(o.exit_code, 1) << o.out << o.err;
  EXPECT_NE(o.out.find("0 of 2 cases done before (1 case stopped while writing its heatmaps: "
                       "checked again)"),
            std::string::npos)
      << o.out;
  EXPECT_NE(o.out.find("clip_noperspective_x_plane"), std::string::npos) << o.out;
  EXPECT_TRUE(fs::exists(out / "cases/clip_noperspective_x_plane/coverage.png"));
  EXPECT_NE(read(out / "journal.jsonl").find("\"heatmaps\":\"written\""), std::string::npos);
  // The journal reads whole again: nothing is left to check.
  const Outcome again = glrefcheck("run --resume '" + out.string() + "'");
  EXPECT_NE(again.out.find("2 of 2 cases done before\n"), std::string::npos) << again.out;
}

// The hostile campaign's W2: a diff stopped while writing its images left those written so far
// unlisted, and the next diff kept them beside its own. Each name is now listed before its file
// is written: a diff whose image writer fails at its first image (no image plugin) has listed
// that image already, with no digest yet, and the next diff clears whatever it finds by it.
TEST_F(EarlierOutputs, ADiffStoppedHalfwayLeavesNoImageUnlisted) {
  const fs::path out = dir_ / "d";
  ASSERT_LE(glrefcheck("diff cases/face_on.json --out '" + out.string() + "'").exit_code, 1);
  ASSERT_TRUE(fs::exists(out / "color.x_error.png"));
  const Outcome stopped =
      glrefcheck("diff cases/attr_mixed_magnitudes.json --out '" + out.string() + "'",
                 "GLRC_IMAGES_PLUGIN=/nonexistent/glrefcheck_images.so");
  EXPECT_NE(stopped.exit_code, 0) << stopped.out << stopped.err;
  const std::string listed = read(out / ".glrefcheck-diff-images");
  EXPECT_NE(listed.find("\n- depth_error.png\n"), std::string::npos) << listed;
  EXPECT_FALSE(fs::exists(out / "color.x_error.png"));  // the last diff's, cleared first
  // As a kill would leave it: the first image written, still without its digest.
  std::ofstream(out / "depth_error.png") << "half an image";
  ASSERT_LE(glrefcheck("diff cases/viewport_tiny.json --out '" + out.string() + "'").exit_code, 1);
  const std::string now = read(out / ".glrefcheck-diff-images");
  for (const auto& e : fs::directory_iterator(out)) {
    const std::string name = e.path().filename().string();
    EXPECT_FALSE(name.starts_with("m.")) << name << " is the stopped diff's";
    if (name.ends_with(".png") || name.ends_with(".exr")) {
      EXPECT_NE(now.find(" " + name + "\n"), std::string::npos) << name << " is not listed";
    }
  }
  EXPECT_NE(read(out / "depth_error.png"), "half an image");
}

// The hostile campaign's U4: `report` on the folder of a run still going said "the run was
// killed". Now it names the run that holds the folder, and writes nothing there.
TEST_F(EarlierOutputs, ReportOnAFolderALiveRunHoldsNamesTheRun) {
  const fs::path out = dir_ / "out", pidfile = dir_ / "worker.pid";
  std::thread run = run_held_at_attr_tiny(out, pidfile);
  const pid_t proxy = wait_for_pid(pidfile);
  ASSERT_GT(proxy, 0);
  const Outcome o = glrefcheck("report '" + out.string() + "'");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
  EXPECT_NE(o.err.find("is in use by another glrefcheck (pid " + std::to_string(parent_of(proxy)) +
                       ": glrefcheck run"),
            std::string::npos)
      << o.err;
  EXPECT_EQ(o.err.find("killed"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(out / "report.html"));
  ASSERT_EQ(kill(parent_of(proxy), SIGINT), 0);
  run.join();
  EXPECT_EQ(glrefcheck("report '" + out.string() + "'").exit_code, 0);
}

}  // namespace

// The hostile campaign's two debatable losses, now refused: a fuzz run into its own folder
// deleted a minimal case the user had edited in failures/, and a run deleted a diff's folder the
// user had put in the run's logs/.
TEST_F(EarlierOutputs, AnEditedMinimalCaseOrAnOutputFolderInsideIsNotReplaced) {
  const fs::path f = dir_ / "f";
  ASSERT_EQ(
      glrefcheck("fuzz --seed 1 --count 20 --generator clip --jobs 1 --out '" + f.string() + "'")
          .exit_code,
      1);
  const fs::path failure = f / "failures/non_finite_noperspective.json";
  std::string text = read(failure);
  ASSERT_NE(text.find("\"description\": \""), std::string::npos);
  text.insert(text.find("\"description\": \"") + 16, "Mine: ");
  std::ofstream(failure) << text;
  const auto before = snapshot(f);
  Outcome o = glrefcheck("fuzz --seed 2 --count 4 --jobs 1 --out '" + f.string() + "'");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
  EXPECT_NE(o.err.find("\"non_finite_noperspective.json\", which was changed since glrefcheck "
                       "wrote it (its stamp no longer matches): move it out of the folder first"),
            std::string::npos)
      << o.err;
  EXPECT_EQ(snapshot(f), before) << differences(before, snapshot(f));

  const fs::path r = dir_ / "r";
  ASSERT_EQ(glrefcheck("run cases/face_on.json --jobs 1 --out '" + r.string() + "'").exit_code, 0);
  ASSERT_LE(glrefcheck("diff cases/face_on.json --out '" + (r / "logs/d").string() + "'").exit_code,
            1);
  const auto run_before = snapshot(r);
  o = glrefcheck("run cases/face_on.json --jobs 1 --out '" + r.string() + "'");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
  EXPECT_NE(o.err.find("logs holds another glrefcheck output folder"), std::string::npos) << o.err;
  EXPECT_EQ(snapshot(r), run_before) << differences(run_before, snapshot(r));
}

// The third hostile campaign (issue 45): `report DIR` replaced a DIR/report.html of the user's,
// `diff` replaced the user's coverage.png in its folder and deleted an image of the last diff the
// user had annotated. Each is now the user's: refused, or kept.
TEST_F(EarlierOutputs, ReportAndDiffReplaceOnlyWhatTheyWroteUnchanged) {
  const fs::path r = dir_ / "r";
  ASSERT_EQ(glrefcheck("run cases/face_on.json --jobs 1 --out '" + r.string() + "'").exit_code, 0);
  ASSERT_EQ(glrefcheck("report '" + r.string() + "'").exit_code, 0);
  ASSERT_EQ(glrefcheck("report '" + r.string() + "'").exit_code, 0);  // its own page: replaced
  std::ofstream(r / "report.html", std::ios::app) << "<!-- my notes -->\n";
  const std::string page = read(r / "report.html");
  Outcome o = glrefcheck("report '" + r.string() + "'");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
  EXPECT_NE(o.err.find("which was changed since glrefcheck wrote it"), std::string::npos) << o.err;
  EXPECT_EQ(read(r / "report.html"), page);

  // diff into the run's folder, which holds a screenshot of the user's named as an image.
  std::ofstream(r / "coverage.png") << "my screenshot";
  o = glrefcheck("diff cases/face_on.json --out '" + r.string() + "'");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
  EXPECT_NE(o.err.find("expected no \"coverage.png\" there but an image the last diff wrote"),
            std::string::npos)
      << o.err;
  EXPECT_EQ(read(r / "coverage.png"), "my screenshot");

  // An image of the last diff the user annotated stays; the others go.
  const fs::path d = dir_ / "d";
  ASSERT_LE(
      glrefcheck("diff cases/attr_mixed_magnitudes.json --out '" + d.string() + "'").exit_code, 1);
  std::ofstream(d / "m.x_error.png", std::ios::app) << "annotated";
  const std::string annotated = read(d / "m.x_error.png");
  ASSERT_LE(glrefcheck("diff cases/face_on.json --out '" + d.string() + "'").exit_code, 1);
  EXPECT_EQ(read(d / "m.x_error.png"), annotated);
  EXPECT_FALSE(fs::exists(d / "m.y_error.png"));
  EXPECT_TRUE(fs::exists(d / "color.x_error.png"));
  // A list edited by hand (a name added) deletes nothing.
  std::ofstream(d / "notes.txt") << "mine";
  std::ofstream(d / ".glrefcheck-diff-images", std::ios::app) << "- notes.txt\n";
  ASSERT_LE(glrefcheck("diff cases/viewport_tiny.json --out '" + d.string() + "'").exit_code, 2);
  EXPECT_EQ(read(d / "notes.txt"), "mine");
}

// The fourth hostile campaign (issue 45): a Ctrl-C (or SIGTERM) before GL was up wrote a run of
// no cases over the folder's earlier results, and a campaign's over its failures/; a refused
// diff had deleted the last diff's images first; a stamped minimal case copied into failures/
// from elsewhere was deleted by the next campaign.
TEST_F(EarlierOutputs, ASignalBeforeGlOrARefusalLeavesTheFolderAsItWas) {
  const fs::path out = dir_ / "out", pidfile = dir_ / "worker.pid";
  ASSERT_EQ(
      glrefcheck("run cases/face_on.json --jobs 1 --html --out '" + out.string() + "'").exit_code,
      0);
  const auto before = snapshot(out);
  for (const auto& [command, signal] :
       {std::pair{std::string("run cases/attr_tiny.json --jobs 1"), SIGINT},
        {std::string("fuzz --count 4 --jobs 1"), SIGTERM}}) {
    SCOPED_TRACE(command);
    // The command into `folder`, its workers held before GL, stopped by the signal.
    const auto stopped_into = [&, &command = command, signal = signal](const fs::path& folder) {
      const Outcome o =
          stopped_before_gl(command + " --out '" + folder.string() + "'", pidfile, signal);
      EXPECT_EQ(o.exit_code, 128 + signal) << o.out << o.err;
      return o;
    };
    Outcome o = stopped_into(out);
    EXPECT_NE(o.out.find("before GL started: " + out.string() + " holds its earlier results"),
              std::string::npos)
        << o.out;
    EXPECT_EQ(snapshot(out), before) << differences(before, snapshot(out));
    // Into a new folder it held no earlier results (the tenth hostile campaign: it said it did).
    const fs::path fresh = dir_ / ("fresh" + std::to_string(signal));
    o = stopped_into(fresh);
    EXPECT_NE(o.out.find("before GL started: " + fresh.string() +
                         " holds no results (it held none before)"),
              std::string::npos)
        << o.out;
  }

  // A refused diff changes nothing: the check comes before the last diff's images are cleared.
  const fs::path d = dir_ / "d";
  ASSERT_LE(glrefcheck("diff cases/face_on.json --out '" + d.string() + "'").exit_code, 1);
  std::ofstream(d / "depth_error.png") << "my annotated copy";
  const auto images = snapshot(d);
  const Outcome refused = glrefcheck("diff cases/face_on.json --out '" + d.string() + "'");
  EXPECT_EQ(refused.exit_code, 2) << refused.out << refused.err;
  EXPECT_EQ(snapshot(d), images) << differences(images, snapshot(d));

  // A stamped case copied into a campaign's failures/ is the user's: refused.
  const fs::path f = dir_ / "f";
  ASSERT_EQ(
      glrefcheck("fuzz --seed 1 --count 20 --generator clip --jobs 1 --out '" + f.string() + "'")
          .exit_code,
      1);
  ASSERT_EQ(glrefcheck("fuzz --generator clip --replay 1:7 --emit '" +
                       (f / "failures/keep_me.json").string() + "'")
                .exit_code,
            0);
  const auto campaign = snapshot(f);
  const Outcome added =
      glrefcheck("fuzz --seed 1 --count 20 --generator clip --jobs 1 --out '" + f.string() + "'");
  EXPECT_EQ(added.exit_code, 2) << added.out << added.err;
  EXPECT_NE(added.err.find("\"keep_me.json\", which the folder's results.json does not list"),
            std::string::npos)
      << added.err;
  EXPECT_EQ(snapshot(f), campaign) << differences(campaign, snapshot(f));
}

// The fifth hostile campaign (issue 45): `run --resume` wrote a case's heatmaps into a diff's
// folder the user had put in the run's cases/ (a fresh run refuses it), and a diff waited for
// good on a FIFO put where one of the last diff's images was.
TEST_F(EarlierOutputs, AResumeRefusesAnOutputFolderInsideAndADiffDoesNotWaitOnAFifo) {
  const fs::path out = dir_ / "out", pidfile = dir_ / "worker.pid";
  std::thread run = run_held_at_attr_tiny(out, pidfile);
  const pid_t proxy = wait_for_pid(pidfile);
  ASSERT_GT(proxy, 0);
  ASSERT_EQ(kill(parent_of(proxy), SIGINT), 0);
  run.join();
  const fs::path inside = out / "cases/attr_tiny";
  ASSERT_LE(glrefcheck("diff cases/face_on.json --out '" + inside.string() + "'").exit_code, 1);
  const auto before = snapshot(inside);
  Outcome o = glrefcheck("run --resume '" + out.string() + "'");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
  EXPECT_NE(o.err.find("holds another glrefcheck output folder"), std::string::npos) << o.err;
  EXPECT_EQ(snapshot(inside), before) << differences(before, snapshot(inside));

  fs::remove(inside / "depth_ratio.png");
  ASSERT_EQ(mkfifo((inside / "depth_ratio.png").c_str(), 0600), 0);
  o = glrefcheck("diff cases/face_on.json --out '" + inside.string() + "'", "timeout 60");
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;  // 124: timeout's, a hang
  EXPECT_NE(o.err.find("\"depth_ratio.png\" there but an image the last diff wrote"),
            std::string::npos)
      << o.err;
}

// The sixth hostile campaign (issue 45): SIGINT in the middle of a merge killed it with the
// folder's earlier merge set aside, there until the next command claimed the folder. A merge
// now stops between two steps and gives it back. Real signals at several moments: each ends in
// the new merge (exit 0) or in the earlier one whole (exit 130, said so), never in between.
TEST_F(EarlierOutputs, AMergeStoppedBySigintGivesTheEarlierMergeBack) {
  const fs::path a = dir_ / "a", b = dir_ / "b", out = dir_ / "merged";
  const std::string shard =
      "run cases/face_on.json cases/viewport_tiny.json --jobs 1 --fraction 2 ";
  ASSERT_EQ(glrefcheck(shard + "--fraction-start 1 --out '" + a.string() + "'").exit_code, 0);
  ASSERT_EQ(glrefcheck(shard + "--fraction-start 2 --out '" + b.string() + "'").exit_code, 0);
  const std::string merge =
      "merge '" + a.string() + "' '" + b.string() + "' --out '" + out.string() + "'";
  ASSERT_EQ(glrefcheck(merge).exit_code, 0);
  auto earlier = snapshot(out);
  // Heatmaps enough that copying them takes a while: a signal lands in the middle.
  // (Named as glrefcheck's images are, glrefcheck their Software: a merge completed replaces
  // them in the next attempt.)
  fs::create_directories(a / "cases/face_on");
  for (int k = 0; k < 20000; ++k)
    std::ofstream(a / "cases/face_on" / ("m" + std::to_string(k) + "_error.png"))
        << "Software glrefcheck " << k;
  int stopped = 0;
  for (const char* delay : {"0.2", "0.4", "0.7", "1.0"}) {
    SCOPED_TRACE(delay);
    // Its stderr by hand: glrefcheck()'s own redirection would apply to `wait`.
    Outcome o = glrefcheck(merge + " 2>'" + (dir_ / "err.txt").string() + "' & pid=$!; sleep " +
                           delay + "; kill -INT $pid; wait $pid");
    o.err = read(dir_ / "err.txt");
    if (o.exit_code == 0) {
      // Whole (a signal before the handler was set, as under a sanitizer's slower start, is
      // ignored: a background job's SIGINT is): the folder's merge from now on.
      EXPECT_TRUE(fs::exists(out / "cases/face_on/m19999_error.png"));
      earlier = snapshot(out);
    } else {
      EXPECT_EQ(o.exit_code, 130) << o.out << o.err;
      EXPECT_NE(o.err.find("interrupted by SIGINT: the output folder holds what it held before"),
                std::string::npos)
          << o.err;
      stopped += o.err.find("interrupted by SIGINT") != std::string::npos;
    }
    EXPECT_FALSE(fs::exists(out / ".glrefcheck-earlier"));
    EXPECT_EQ(snapshot(out), earlier) << differences(earlier, snapshot(out));
  }
  EXPECT_GE(stopped, 1) << "no signal landed in the middle of the merge";
}

// The seventh hostile campaign (issue 45): a run deleted a note put in its cases/ or logs/, a
// report.html a person annotated, and the --baseline it was given when that was the folder's own
// failures.csv (the natural next baseline), which it replaced with a list of no expected
// failure; identify replaced any identify.json. Each is refused now, and left as it was.
TEST_F(EarlierOutputs, ARunReplacesOnlyItsOwnFiles) {
  const fs::path out = dir_ / "out";
  const std::string run = "run cases/face_on.json --jobs 1 --out '" + out.string() + "'";
  ASSERT_EQ(glrefcheck(run).exit_code, 0);
  const auto refused = [&](const std::string& command, const fs::path& file,
                           const std::string& says) {
    const std::string before = read(file);
    const Outcome o = glrefcheck(command);
    EXPECT_EQ(o.exit_code, 2) << command << o.out << o.err;
    EXPECT_NE(o.err.find(says), std::string::npos) << o.err;
    EXPECT_EQ(read(file), before) << file;
  };
  fs::create_directories(out / "cases");
  std::ofstream(out / "cases/notes.txt") << "mine\n";
  refused(run, out / "cases/notes.txt", "notes.txt is not a case's folder of heatmaps");
  fs::remove(out / "cases/notes.txt");
  fs::create_directories(out / "cases/face_on");
  std::ofstream(out / "cases/face_on/notes.txt") << "mine\n";
  refused(run, out / "cases/face_on/notes.txt", "notes.txt is not a heatmap glrefcheck wrote");
  fs::remove_all(out / "cases/face_on");
  fs::create_directories(out / "logs");
  std::ofstream(out / "logs/mine.log") << "mine\n";
  refused(run, out / "logs/mine.log", "mine.log is not a worker's log");
  fs::remove(out / "logs/mine.log");
  ASSERT_EQ(glrefcheck("report '" + out.string() + "'").exit_code, 0);
  std::ofstream(out / "report.html", std::ios::app) << "<!-- mine -->\n";
  refused(run, out / "report.html", "report.html is not a page glrefcheck wrote, or was changed");
  fs::remove(out / "report.html");
  // A comparison's page put there (the tenth hostile campaign: `report` refused it, a run did not).
  const Outcome compared = glrefcheck("compare '" + out.string() + "' '" + out.string() +
                                      "' --html '" + (out / "report.html").string() + "'");
  ASSERT_LE(compared.exit_code, 1) << compared.out << compared.err;
  refused(run, out / "report.html",
          "report.html is a page glrefcheck compare wrote, not the folder's report");
  fs::remove(out / "report.html");
  std::ofstream(out / "failures.csv", std::ios::app) << "face_on,Fail\n";
  refused(run + " --baseline '" + (out / "failures.csv").string() + "'", out / "failures.csv",
          "holds this run's --baseline");
  refused("fuzz --count 2 --baseline '" + (out / "results.csv").string() + "' --out '" +
              out.string() + "'",
          out / "results.csv", "holds this campaign's --baseline");
  // identify: a file of its own is replaced, one of a person's is not.
  ASSERT_EQ(glrefcheck("identify --out '" + out.string() + "'").exit_code, 0);
  ASSERT_EQ(glrefcheck("identify --out '" + out.string() + "'").exit_code, 0);
  std::ofstream(out / "identify.json") << "{\"my\": 1}\n";
  refused("identify --out '" + out.string() + "'", out / "identify.json",
          "which glrefcheck did not write (it holds no stamp)");
  EXPECT_EQ(glrefcheck(run).exit_code, 0);  // the run's own files it replaces, as ever
  // A temporary file a glrefcheck killed outright left (the eighth campaign: a merge's
  // .junit.xml.tmp-PID stayed for good) goes with the next claim of the folder.
  const pid_t gone = fork();
  if (gone == 0) _exit(0);
  ASSERT_GT(gone, 0);
  waitpid(gone, nullptr, 0);
  const fs::path stale = out / (".junit.xml.tmp-" + std::to_string(gone));
  std::ofstream(stale) << "half";
  EXPECT_EQ(glrefcheck(run).exit_code, 0);
  EXPECT_FALSE(fs::exists(stale));
}

// A run into a campaign's folder left the campaign's failures/ beside its results, and the next
// campaign there refused them as files a person added. The run replaces them with the rest.
TEST_F(EarlierOutputs, ARunIntoACampaignsFolderReplacesItsFailures) {
  const fs::path out = dir_ / "out";
  const std::string campaign =
      "fuzz --seed 1 --count 20 --generator clip --jobs 1 --out '" + out.string() + "'";
  ASSERT_EQ(glrefcheck(campaign).exit_code, 1);
  ASSERT_TRUE(fs::exists(out / "failures"));
  ASSERT_EQ(glrefcheck("run cases/face_on.json --jobs 1 --out '" + out.string() + "'").exit_code,
            0);
  EXPECT_FALSE(fs::exists(out / "failures"));
  const Outcome again = glrefcheck(campaign);
  EXPECT_EQ(again.exit_code, 1) << again.out << again.err;
}

// A resumed run left the page `report` wrote of it as it stopped ("interrupted after 1 case")
// beside its whole results; compare on the folder of a live run called it killed.
TEST_F(EarlierOutputs, AResumeRefreshesTheFoldersPageAndALiveRunIsNamed) {
  const fs::path out = dir_ / "out", pidfile = dir_ / "worker.pid";
  std::thread run = run_held_at_attr_tiny(out, pidfile);
  const pid_t proxy = wait_for_pid(pidfile);
  ASSERT_GT(proxy, 0);
  const Outcome live = glrefcheck("compare '" + out.string() + "' '" + out.string() + "'");
  EXPECT_EQ(live.exit_code, 2) << live.out << live.err;
  EXPECT_NE(live.err.find("another glrefcheck is writing into it (pid "), std::string::npos)
      << live.err;
  ASSERT_EQ(kill(parent_of(proxy), SIGINT), 0);
  run.join();
  ASSERT_EQ(glrefcheck("report '" + out.string() + "'").exit_code, 0);
  ASSERT_NE(read(out / "report.html").find("interrupted"), std::string::npos);
  const Outcome resumed = glrefcheck("run --resume '" + out.string() + "'");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.out << resumed.err;
  EXPECT_EQ(read(out / "report.html").find("interrupted"), std::string::npos);
  EXPECT_NE(read(out / "report.html").find("attr_tiny"), std::string::npos);
}

// A model cache that is a FIFO (a hostile or broken $XDG_CACHE_HOME) held a run in open() for
// good, beyond SIGINT and SIGTERM; it is not read now.
TEST_F(EarlierOutputs, AModelCacheThatIsAFifoIsNotWaitedFor) {
  fs::create_directories(dir_ / "cache/glrefcheck");
  ASSERT_EQ(mkfifo((dir_ / "cache/glrefcheck/models.json").c_str(), 0600), 0);
  ASSERT_EQ(mkfifo((dir_ / "cache/glrefcheck/driver_digests.json").c_str(), 0600), 0);
  const Outcome o =
      glrefcheck("run cases/face_on.json --jobs 1 --out '" + (dir_ / "out").string() + "'",
                 "XDG_CACHE_HOME='" + (dir_ / "cache").string() + "' timeout 60");
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;  // 124: timeout's, a hang
}

// The ninth hostile campaign (issue 45): a campaign killed outright (kill -9) after it had
// written a minimal case left failures/ with no results.json to list it, and every later campaign
// there refused the case as a person's. The campaign names its cases as it writes them
// (kFailuresWritten): the next campaign replaces them; a case a person adds is still refused.
TEST_F(EarlierOutputs, ACampaignKilledOutrightLeavesNothingThatBlocksTheNext) {
  const fs::path out = dir_ / "out";
  const std::string campaign =
      "fuzz --seed 1 --generator clip --jobs 1 --out '" + out.string() + "'";
  // Killed once its first minimal case is there, long before its 600 s are up.
  const Outcome killed = glrefcheck(
      campaign + " --time 600 >/dev/null & pid=$!; for k in $(seq 1200); do ls '" +
      (out / "failures").string() + "'/*.json >/dev/null 2>&1 && break; sleep 0.1; done; " +
      "kill -9 $pid; wait $pid");
  ASSERT_EQ(killed.exit_code, 128 + SIGKILL) << killed.out << killed.err;
  ASSERT_FALSE(fs::exists(out / "results.json"));
  ASSERT_FALSE(fs::is_empty(out / "failures"));

  // A person's copy of a minimal case put beside the killed campaign's is theirs: refused.
  ASSERT_EQ(glrefcheck("fuzz --generator clip --replay 1:7 --emit '" +
                       (out / "failures/keep_me.json").string() + "'")
                .exit_code,
            0);
  const auto left = snapshot(out);
  const Outcome refused = glrefcheck(campaign + " --count 20");
  EXPECT_EQ(refused.exit_code, 2) << refused.out << refused.err;
  EXPECT_NE(refused.err.find("\"keep_me.json\", which the folder's results.json does not list"),
            std::string::npos)
      << refused.err;
  EXPECT_EQ(snapshot(out), left) << differences(left, snapshot(out));

  fs::remove(out / "failures/keep_me.json");
  const Outcome next = glrefcheck(campaign + " --count 20");
  EXPECT_EQ(next.exit_code, 1) << next.out << next.err;
  EXPECT_TRUE(fs::exists(out / "results.json"));
  EXPECT_FALSE(fs::exists(out / ".glrefcheck-failures"));  // results.json lists them now
  const std::string results = read(out / "results.json");
  for (const auto& e : fs::directory_iterator(out / "failures"))
    EXPECT_NE(results.find("\"failures/" + e.path().filename().string() + "\""), std::string::npos)
        << e.path();
}

// The tenth hostile campaign (issue 45): a run deleted a picture a person put among a case's
// heatmaps (cases/<case>/my_annotation.png), in a folder of their own in cases/, and a log named
// like a worker's: anything named *.png, *.exr or worker-*.log passed for glrefcheck's. Its
// images name glrefcheck as their Software, its logs open with its line: the rest is refused.
TEST_F(EarlierOutputs, APictureOrLogNamedLikeARunsIsNotTakenForOne) {
  const fs::path out = dir_ / "out";
  const std::string run =
      "run --filter 'clip_noperspective_x_plane$' --jobs 1 --out '" + out.string() + "'";
  ASSERT_EQ(glrefcheck(run).exit_code, 1);
  const fs::path heatmaps = out / "cases/clip_noperspective_x_plane";
  ASSERT_TRUE(fs::exists(heatmaps / "coverage.png"));
  ASSERT_TRUE(fs::exists(out / "logs/worker-1.log"));
  const auto refused = [&](const fs::path& file, const std::string& says) {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << "mine\n";
    const auto before = snapshot(out);
    const Outcome o = glrefcheck(run);
    EXPECT_EQ(o.exit_code, 2) << file << o.out << o.err;
    EXPECT_NE(o.err.find(file.filename().string() + " " + says), std::string::npos) << o.err;
    EXPECT_EQ(snapshot(out), before) << differences(before, snapshot(out));
    fs::remove(file);
  };
  refused(heatmaps / "my_annotation.png", "is not a heatmap glrefcheck wrote");
  refused(out / "cases/mine/shot.png", "is not a heatmap glrefcheck wrote");
  fs::remove_all(out / "cases/mine");
  refused(out / "logs/worker-99.log", "is not a worker's log glrefcheck wrote");
  // The run's own images and logs it replaces, as before.
  const Outcome again = glrefcheck(run);
  EXPECT_EQ(again.exit_code, 1) << again.out << again.err;
  EXPECT_TRUE(fs::exists(heatmaps / "coverage.png"));
}

// The eleventh hostile campaign (issue 45): a folder of a person's under a file's name
// (junit.xml/, results.csv/ with notes in it) was deleted with what it held by the next run,
// merge or campaign there, and a file under a folder's name (logs) replaced; report.html as a
// folder gave the C++ library's words. Each is refused in one line, the folder as it was.
TEST_F(EarlierOutputs, AnOutputOfAnotherKindUnderItsNameIsRefused) {
  const fs::path out = dir_ / "out";
  const std::string run = "run cases/face_on.json --jobs 1 --out '" + out.string() + "'";
  ASSERT_EQ(glrefcheck(run).exit_code, 0);
  const auto refused = [&](const std::string& command, const std::string& says) {
    const auto before = snapshot(out);
    const Outcome o = glrefcheck(command);
    EXPECT_EQ(o.exit_code, 2) << command << o.out << o.err;
    EXPECT_NE(o.err.find(says), std::string::npos) << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
    EXPECT_EQ(snapshot(out), before) << differences(before, snapshot(out));
  };
  fs::remove(out / "junit.xml");
  fs::create_directories(out / "junit.xml");
  std::ofstream(out / "junit.xml/notes.txt") << "precious\n";
  refused(run, "junit.xml is not a regular file, where glrefcheck writes a file of that name");
  fs::remove_all(out / "junit.xml");
  fs::remove_all(out / "logs");
  std::ofstream(out / "logs") << "precious\n";
  refused(run, "logs is not a folder, where glrefcheck writes a folder of that name");
  fs::remove(out / "logs");
  fs::create_directories(out / "report.html");
  refused(run + " --html",
          "report.html is not a regular file, where glrefcheck writes a file of that name");
  fs::remove_all(out / "report.html");
  // A campaign's folder the same (its results.csv).
  const fs::path f = dir_ / "f";
  const std::string campaign =
      "fuzz --seed 1 --count 4 --generator clip --jobs 1 --out '" + f.string() + "'";
  ASSERT_LE(glrefcheck(campaign).exit_code, 1);
  fs::remove(f / "results.csv");
  fs::create_directories(f / "results.csv");
  std::ofstream(f / "results.csv/notes.txt") << "precious\n";
  const Outcome o = glrefcheck(campaign);
  EXPECT_EQ(o.exit_code, 2) << o.out << o.err;
  EXPECT_EQ(read(f / "results.csv/notes.txt"), "precious\n");
  // --device without egl-device was ignored without a word.
  const Outcome device = glrefcheck("run cases/face_on.json --device 3 --jobs 1 --out '" +
                                    (dir_ / "d").string() + "'");
  EXPECT_EQ(device.exit_code, 2) << device.out << device.err;
  EXPECT_NE(device.err.find("--device: expected with --backend egl-device"), std::string::npos)
      << device.err;
}
