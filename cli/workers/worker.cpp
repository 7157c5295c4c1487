// The child side of cli/workers/workers.hpp: one GL context, many cases.
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "casefile/casefile.hpp"
#include "casefile/wire.hpp"
#include "cli/identify.hpp"
#include "cli/workers/protocol.hpp"
#include "cli/workers/workers.hpp"
#include "identify/model_cache.hpp"
#include "report/report.hpp"

namespace glrc::cli {

namespace {

// Results go to a private copy of stdout; the real fd 1 is pointed at stderr (the log), so
// whatever a driver prints cannot corrupt the protocol.
class Channel {
 public:
  Channel() : fd_(dup(STDOUT_FILENO)) { dup2(STDERR_FILENO, STDOUT_FILENO); }
  void send(const nlohmann::json& j) const {
    send_line(j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  }
  void send_raw_result(size_t index, const std::string& result_json, bool images) const {
    send_line(result_line(index, result_json, images));
  }

 private:
  void send_line(std::string line) const {
    line += '\n';
    for (size_t done = 0; done < line.size();) {
      const ssize_t n = write(fd_, line.data() + done, line.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) std::exit(3);  // the runner is gone: nobody to report to
      done += size_t(n);
    }
  }
  int fd_;
};

// A checked case, with its frames kept for the heatmaps that follow the verdict.
struct Outcome {
  Case c;
  check::Checked checked;
};

// `last`: the previous case's frames, whose memory this case's reuse (check_with_frames).
Outcome check_one(const nlohmann::json& job, const check::CheckOptions& o, gl::Renderer& renderer,
                  check::Checked last) {
  Outcome out;
  try {
    // The runner has read and validated the case already and sends it whole: a case file is
    // parsed once per run. A job naming only a file is read here.
    out.c = job.contains("case") ? casefile::from_wire(job["case"])
                                 : casefile::load(job.at("file").get<std::string>());
  } catch (const std::exception& e) {
    CaseResult& r = out.checked.result;
    r.name = job.at("name"), r.status = r.outcome = Status::error, r.message = e.what();
    return out;
  }
  out.checked = check::check_with_frames(out.c, renderer, o, std::move(last));
  return out;
}

// A failing case's heatmaps, in <out>/cases/<case>/ for the HTML report and anyone triaging
// the run. Returns why there are none, or "".
// A case checked slice by slice holds no whole frame: its pictures are made slice by slice again,
// from the reference's rows and GL's, which still holds the case's drawing.
std::string write_images(Outcome& done, const Options& o, const check::CheckOptions& judged,
                         gl::Renderer& renderer) {
  try {
    const std::filesystem::path dir = std::filesystem::path(o.out) / "cases" / done.c.name;
    if (done.checked.streamed) {
      const int reported = renderer.info().subpixel_bits;
      report::write_streamed_diff_images(
          dir, done.c, done.checked.result, check::slice_rows(done.c, judged),
          [&](int y0, int rows) {
            return std::pair{check::expectation_rows(done.c, judged, reported, y0, rows),
                             renderer.read_rows(done.c, y0, rows)};
          });
      return "";
    }
    // The heatmaps show every pixel's allowance.
    complete_allowance(done.checked.expected, judged.threads);
    report::write_diff_images(dir, done.c, done.checked.expected, done.checked.gl,
                              done.checked.result);
    return "";
  } catch (const std::exception& e) {
    std::cerr << "glrefcheck worker: " << done.c.name << ": no heatmaps: " << e.what() << '\n';
    return e.what();
  }
}

// One line of standard input, without its newline; false at its end. POSIX getline on stdin's
// own buffer: std::getline on the synchronised std::cin takes a character at a time through
// getc and ungetc, and a job of a few thousand triangles is a line of megabytes (a twentieth of
// a fuzz campaign's time went there).
bool read_line(std::string& line) {
  char* buffer = nullptr;
  size_t capacity = 0;
  const ssize_t n = ::getline(&buffer, &capacity, stdin);
  if (n >= 0) line.assign(buffer, size_t(n) - (n > 0 && buffer[n - 1] == '\n' ? 1 : 0));
  std::free(buffer);
  return n >= 0;
}

}  // namespace

int cmd_worker() {
  const Channel channel;
  std::string line;
  if (!read_line(line)) return 2;
  Options o;
  std::unique_ptr<gl::Renderer> renderer;
  try {
    o = options_from_json(line);
    renderer = open_renderer(o);
  } catch (const std::exception& e) {
    channel.send({{"error", e.what()}});
    return 2;
  }
  const gl::GlInfo& gl = renderer->info();
  channel.send(hello_message(gl, identify::driver_files(gl)));
  check::Checked last;  // the last case checked, its frames' memory for the next case's
  while (read_line(line)) {
    const auto job = nlohmann::json::parse(line);
    if (job.contains("identify")) {
      try {
        channel.send({{"identified", identify::model_json(identify::identify_model(*renderer))}});
      } catch (const std::exception& e) {
        channel.send({{"identify_error", e.what()}});
      }
      continue;
    }
    const size_t index = job.at("index");
    Outcome done;
    check::CheckOptions judged = check_options(o);
    // Only a failing case's heatmaps need every pixel's allowance (write_images).
    judged.deferred_allowance = true;
    try {
      // Every case of the run is judged by the run's model, which the runner chose.
      const auto model = identify::model_from_json(job.at("model"));
      if (!model) throw std::runtime_error("a job without a valid model: " + line);
      judged.model = *model;
      done = check_one(job, judged, *renderer, std::exchange(last, {}));
    } catch (const std::exception& e) {
      done.checked = check::Checked{};
      CaseResult& r = done.checked.result;
      r.name = job.at("name"), r.status = r.outcome = Status::error, r.message = e.what();
    }
    // The verdict first: heatmaps of a large frame take long and much memory, and a worker
    // killed while writing them must not take the verdict with it.
    const bool images = done.checked.result.outcome == Status::fail && job.value("images", true);
    channel.send_raw_result(index, report::case_result_json(done.checked.result), images);
    if (images) {
      const std::string error = write_images(done, o, judged, *renderer);
      nlohmann::json note = {{"images_done", index}};
      if (!error.empty()) note["images_error"] = error;
      channel.send(note);
    }
    last = std::move(done.checked);
  }
  return 0;
}

}  // namespace glrc::cli
