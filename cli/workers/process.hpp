// A child process on pipes: what the worker pool needs of fork, exec, poll and kill, in one
// place. The child's stdin and stdout are pipes to us, its stderr is appended to a log file; it
// runs in its own process group (a terminal's Ctrl-C reaches the parent only, which stops a run
// in order) and the kernel kills it when the parent dies (PR_SET_PDEATHSIG), so a child stuck
// in a hung driver never outlives a parent killed with -9.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glrc::cli {

// This program's own file (/proc/self/exe), to start a copy of it; std::runtime_error when it
// cannot be found.
std::string self_executable();
// This process's environment with `overrides` (NAME, value) replacing or adding variables, as
// NAME=value strings for a child.
std::vector<std::string> environment_with(
    const std::vector<std::pair<std::string, std::string>>& overrides);

// GLIBC_TUNABLES for a child that renders (a GL worker): this process's value with
// glibc.malloc.hugetlb=1 added, unless it names that tunable already. glibc (2.35 and later) then
// asks for transparent huge pages on the large blocks malloc maps, which Mesa's drivers clear
// and the frames fill: on a kernel that gives huge pages only where asked (enabled = madvise,
// common on VMs) a fault per 4 KiB page otherwise costs more than the writes (measured on a
// 2-core VM: softpipe's context creation 0.4 s of a 0.57 s run, 0.17 s with it). Speed only:
// no value changes; an older glibc ignores tunables it does not know.
std::pair<std::string, std::string> huge_page_malloc_tunable();
// The same for jemalloc, the programs' allocator where the build links it (GLRC_MALLOC,
// CMakeLists.txt): MALLOC_CONF with thp:always added (madvise(MADV_HUGEPAGE) on what it maps),
// unless it names thp already. Measured: llvmpipe drawing and reading back 1024x1024 with 18
// channels took 30,000 page faults without it, 4,300 with it (glibc with hugetlb=1: 5,300).
// Ignored by any other allocator.
std::pair<std::string, std::string> huge_page_jemalloc_conf();

// The first line of every log a ChildProcess starts: a run, merge or campaign replaces in its
// logs/ only logs that open with it, never a person's file named like one.
inline constexpr std::string_view kChildLogHeader = "glrefcheck: a worker's standard error\n";

class ChildProcess {
 public:
  ChildProcess() = default;
  // Starts argv[0] (a path) with `argv` and the environment `env` (NAME=value each), stderr
  // appended to `log` (kChildLogHeader first, where it is new or empty). Throws std::runtime_error
  // when no pipe, log or process can be had.
  ChildProcess(const std::vector<std::string>& argv, const std::vector<std::string>& env,
               const std::filesystem::path& log);
  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&& other) noexcept;
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  // Kills a child still running, and waits for it: none is ever left behind.
  ~ChildProcess();

  bool running() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }
  // Its stdout, for poll().
  int output_fd() const { return from_; }

  // Writes all of `text` to its stdin. Returns false when it cannot (it died: reading its
  // output then says so). SIGPIPE must be ignored by the caller's process.
  bool send(const std::string& text);
  // One read() of its stdout, appended to `into`: the bytes read, 0 at its end (it exited or
  // closed stdout), -1 for an interrupted read to retry.
  long read_some(std::string& into);

  // After its output ended: waits for it and says how it ended ("exited with code 1",
  // "killed by signal 11 (Segmentation fault)"). What is left of its process group is killed.
  std::string wait();
  // Ends it now: SIGKILL to its process group (it and the processes it started), then waits.
  void kill_now();
  // Closes its stdin (a worker then finishes and exits) and waits for it.
  void finish();

  // The last lines it wrote to its log since it started (several children may share one log,
  // one after the other), newlines as '|', at most `max_chars`: what a driver said before dying.
  std::string log_tail(size_t max_chars = 600) const;

 private:
  void close_pipes();
  pid_t pid_ = -1;
  int to_ = -1, from_ = -1;  // its stdin, its stdout
  std::filesystem::path log_;
  long long log_start_ = 0;
};

}  // namespace glrc::cli
