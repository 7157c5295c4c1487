#include "cli/interrupts.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <stdexcept>

namespace glrc::cli {
namespace {

int g_interrupt_pipe[2] = {-1, -1};
volatile sig_atomic_t g_signal = 0;

extern "C" void on_interrupt(int sig) {
  const int saved = errno;
  if (!g_signal) g_signal = sig;
  const char byte = 1;
  [[maybe_unused]] const ssize_t n = write(g_interrupt_pipe[1], &byte, 1);
  errno = saved;
}

}  // namespace

int catch_interrupts() {
  if (g_interrupt_pipe[0] < 0 && pipe2(g_interrupt_pipe, O_CLOEXEC | O_NONBLOCK) != 0)
    throw std::runtime_error("cannot make a pipe for SIGINT and SIGTERM");
  struct sigaction sa = {};
  sa.sa_handler = on_interrupt;
  // Restarted: a write to stdout or the journal must not fail because a signal came; the pool's
  // poll() returns at once all the same (poll is never restarted, and it watches the pipe).
  sa.sa_flags = SA_RESTART;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  return g_interrupt_pipe[0];
}

int caught_signal() {
  return int(g_signal);
}

const char* signal_name(int sig) {
  return sig == SIGTERM ? "SIGTERM" : "SIGINT";
}

void stop_if_interrupted() {
  if (g_signal) throw Interrupted{int(g_signal)};
}

}  // namespace glrc::cli
