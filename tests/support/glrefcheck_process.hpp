// Runs the built glrefcheck as a user would, for the command-line tests.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

namespace glrc::test {

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

// Runs glrefcheck with the given arguments in the source folder; stdout and stderr apart.
// `env`: shell variable assignments for it, e.g. "XDG_CACHE_HOME=/tmp/x".
inline Outcome glrefcheck(const std::string& args, const std::string& env = "") {
  const std::filesystem::path err_file = std::filesystem::temp_directory_path() /
                                         ("glrc_cli_stderr_" + std::to_string(getpid()) + ".txt");
  const std::string cmd = std::string("cd '") + GLRC_SOURCE_DIR + "' && " + env + " '" +
                          GLRC_BINARY_DIR + "/glrefcheck' " + args + " 2>'" + err_file.string() +
                          "'";
  Outcome o;
  FILE* p = popen(cmd.c_str(), "r");
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0)
    o.out.append(buf, n);
  const int status = pclose(p);
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err_file);
  o.err.assign(std::istreambuf_iterator<char>(e), {});
  // Aborted (a sanitizer's report, or LeakSanitizer's tracer crashing among Mesa's threads at
  // exit): its stderr in the test's output whatever the test checks, so that the log says which
  // (scripts/sanitize.sh runs a test again only when its log shows the tracer's crash).
  if (o.exit_code == 128 + SIGABRT || o.exit_code == -1)
    std::fprintf(stderr, "glrefcheck %s: exit %d, its stderr:\n%s\n", args.c_str(), o.exit_code,
                 o.err.c_str());
  return o;
}

// `run`'s option for workers under tests/tools/worker_proxy.py with `flags` (--stall-case RE,
// --stall-images RE, --pidfile FILE, --crash-on-identify): real workers that hang or die where
// a test wants them to, as a driver would.
inline std::string proxied_workers(const std::string& flags) {
  return std::string(" --worker-wrapper \"'") + GLRC_SOURCE_DIR + "/tests/tools/worker_proxy.py' " +
         flags + "\"";
}

// The pid a worker stalled by worker_proxy.py (--stall-case, --stall-images) wrote to its
// --pidfile, once it has; 0 if none did within 60 s.
inline pid_t wait_for_pid(const std::filesystem::path& pidfile) {
  pid_t pid = 0;
  for (int k = 0; k < 1200 && !pid; ++k) {
    std::ifstream in(pidfile);
    if (!(in >> pid)) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return pid;
}

// The parent of process `pid` (/proc), 0 if it cannot be read: the runner of a worker.
inline pid_t parent_of(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  // pid (comm) state ppid ...: comm may hold spaces, so read after its closing parenthesis.
  const size_t close = text.rfind(')');
  if (close == std::string::npos) return 0;
  char state = 0;
  int ppid = 0;
  if (std::sscanf(text.c_str() + close + 1, " %c %d", &state, &ppid) != 2) return 0;
  return ppid;
}

// Whether process `pid` ended within `limit`: gone, or a zombie waiting for init, either way
// no longer running.
inline bool ended_within(pid_t pid, std::chrono::seconds limit) {
  const auto until = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < until) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    std::string text((std::istreambuf_iterator<char>(in)), {});
    const size_t close = text.rfind(')');
    if (!in || close == std::string::npos || text[close + 2] == 'Z' || text[close + 2] == 'X')
      return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

}  // namespace glrc::test
