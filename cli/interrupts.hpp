// SIGINT and SIGTERM during `run`: the handler only records the signal and writes a byte to a
// pipe the worker pool polls, so the run stops between two results and writes what finished.
#pragma once

namespace glrc::cli {

// Installs the handlers (once); returns the pipe's read end for the pool to poll. Throws
// std::runtime_error when no pipe can be made.
int catch_interrupts();
// The first signal caught (SIGINT or SIGTERM), or 0.
int caught_signal();

}  // namespace glrc::cli
