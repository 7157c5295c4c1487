// SIGINT and SIGTERM during `run`, `fuzz` and `merge`: the handler only records the signal and
// writes a byte to a pipe the worker pool polls, so the run stops between two results and writes
// what finished; a merge stops between two steps and gives the folder's earlier results back.
#pragma once

namespace glrc::cli {

// Installs the handlers (once); returns the pipe's read end for the pool to poll. Throws
// std::runtime_error when no pipe can be made.
int catch_interrupts();
// The first signal caught (SIGINT or SIGTERM), or 0.
int caught_signal();
// "SIGINT" or "SIGTERM".
const char* signal_name(int sig);

// Thrown by stop_if_interrupted once a signal was caught: the destructors on its way out give
// back whatever was set aside (EarlierOutputs), and main exits 128 + `signal`.
struct Interrupted {
  int signal;
};
void stop_if_interrupted();

}  // namespace glrc::cli
