#include "cli/workers/process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/core.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <utility>

extern char** environ;

namespace glrc::cli {
namespace {

std::string describe_exit(int status) {
  if (WIFSIGNALED(status))
    return fmt::format("killed by signal {} ({})", WTERMSIG(status), strsignal(WTERMSIG(status)));
  if (WIFEXITED(status)) return fmt::format("exited with code {}", WEXITSTATUS(status));
  return "ended";
}

}  // namespace

std::string self_executable() {
  char buf[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) throw std::runtime_error("cannot find this program's own file (/proc/self/exe)");
  return std::string(buf, size_t(n));
}

std::vector<std::string> environment_with(
    const std::vector<std::pair<std::string, std::string>>& overrides) {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) {
    const std::string var(*e);
    bool replaced = false;
    for (const auto& [name, value] : overrides)
      replaced = replaced || var.starts_with(name + "=");
    if (!replaced) env.push_back(var);
  }
  for (const auto& [name, value] : overrides)
    env.push_back(name + "=" + value);
  return env;
}

namespace {

// The variable `name` as this process has it, with `setting` appended after `separator` unless
// its value names `key` already (the user's own choice stays).
std::pair<std::string, std::string> with_setting(const std::string& name, const std::string& key,
                                                 const std::string& separator,
                                                 const std::string& setting) {
  const char* given = std::getenv(name.c_str());
  std::string value = given ? given : "";
  if (value.find(key) == std::string::npos) value += (value.empty() ? "" : separator) + setting;
  return {name, value};
}

}  // namespace

std::pair<std::string, std::string> huge_page_malloc_tunable() {
  return with_setting("GLIBC_TUNABLES", "glibc.malloc.hugetlb", ":", "glibc.malloc.hugetlb=1");
}

std::pair<std::string, std::string> huge_page_jemalloc_conf() {
  return with_setting("MALLOC_CONF", "thp:", ",", "thp:always");
}

ChildProcess::ChildProcess(const std::vector<std::string>& argv_text,
                           const std::vector<std::string>& env_text,
                           const std::filesystem::path& log)
    : log_(log) {
  int in_pipe[2], out_pipe[2];
  if (pipe2(in_pipe, O_CLOEXEC) != 0) throw std::runtime_error("cannot make a pipe for a worker");
  if (pipe2(out_pipe, O_CLOEXEC) != 0) {
    close(in_pipe[0]), close(in_pipe[1]);
    throw std::runtime_error("cannot make a pipe for a worker");
  }
  const int log_fd = open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (log_fd < 0) {
    close(in_pipe[0]), close(in_pipe[1]), close(out_pipe[0]), close(out_pipe[1]);
    throw std::runtime_error("cannot write " + log.string());
  }
  log_start_ = lseek(log_fd, 0, SEEK_END);
  if (log_start_ == 0 && write(log_fd, kChildLogHeader.data(), kChildLogHeader.size()) ==
                             ssize_t(kChildLogHeader.size()))
    log_start_ = static_cast<long long>(kChildLogHeader.size());
  // Built before fork: the child may only call async-signal-safe functions.
  std::vector<std::string> args = argv_text, env = env_text;
  std::vector<char*> argv, envp;
  for (auto& a : args)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  for (auto& e : env)
    envp.push_back(e.data());
  envp.push_back(nullptr);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    close(in_pipe[0]), close(in_pipe[1]), close(out_pipe[0]), close(out_pipe[1]), close(log_fd);
    throw std::runtime_error("cannot start a worker process (fork failed)");
  }
  if (pid == 0) {
    // Killed with the parent; and if the parent went before this line, it goes now.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);
    setpgid(0, 0);
    dup2(in_pipe[0], STDIN_FILENO);
    dup2(out_pipe[1], STDOUT_FILENO);
    dup2(log_fd, STDERR_FILENO);
    execve(argv[0], argv.data(), envp.data());
    _exit(127);
  }
  close(in_pipe[0]);
  close(out_pipe[1]);
  close(log_fd);
  pid_ = pid, to_ = in_pipe[1], from_ = out_pipe[0];
}

ChildProcess::ChildProcess(ChildProcess&& other) noexcept {
  *this = std::move(other);
}

ChildProcess& ChildProcess::operator=(ChildProcess&& other) noexcept {
  if (this != &other) {
    if (running()) kill_now();
    pid_ = std::exchange(other.pid_, -1);
    to_ = std::exchange(other.to_, -1);
    from_ = std::exchange(other.from_, -1);
    log_ = std::move(other.log_);
    log_start_ = other.log_start_;
  }
  return *this;
}

ChildProcess::~ChildProcess() {
  if (running()) kill_now();
}

bool ChildProcess::send(const std::string& text) {
  for (size_t done = 0; done < text.size();) {
    const ssize_t n = write(to_, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += size_t(n);
  }
  return true;
}

long ChildProcess::read_some(std::string& into) {
  char buf[65536];
  const ssize_t n = read(from_, buf, sizeof buf);
  if (n < 0 && errno == EINTR) return -1;
  if (n <= 0) return 0;
  into.append(buf, size_t(n));
  return long(n);
}

void ChildProcess::close_pipes() {
  if (to_ >= 0) close(to_);
  if (from_ >= 0) close(from_);
  to_ = from_ = -1;
}

std::string ChildProcess::wait() {
  // What it started and left behind (a wrapper's worker) goes with it. Before waitpid: until
  // the child is reaped its pid cannot become another process group's id. A child that closed
  // its output while exiting keeps its exit status: that was set before its files were closed.
  kill(-pid_, SIGKILL);
  int status = 0;
  waitpid(pid_, &status, 0);
  close_pipes();
  pid_ = -1;
  return describe_exit(status);
}

void ChildProcess::kill_now() {
  // Its whole process group: a wrapper (cli/workers/workers.hpp) and the worker it started. The
  // child itself too, should it be killed before its setpgid.
  kill(-pid_, SIGKILL);
  kill(pid_, SIGKILL);
  waitpid(pid_, nullptr, 0);
  close_pipes();
  pid_ = -1;
}

void ChildProcess::finish() {
  close_pipes();
  waitpid(pid_, nullptr, 0);
  pid_ = -1;
}

std::string ChildProcess::log_tail(size_t max_chars) const {
  std::ifstream in(log_, std::ios::binary);
  in.seekg(log_start_);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  if (text.size() > max_chars) text = "..." + text.substr(text.size() - max_chars);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
    text.pop_back();
  for (char& ch : text)
    if (ch == '\n') ch = '|';
  return text;
}

}  // namespace glrc::cli
