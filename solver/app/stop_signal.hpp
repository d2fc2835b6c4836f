#pragma once
// SIGINT and SIGTERM ask a run to stop cleanly: the handler only records the signal, the
// run loop (solver/app/run.cpp) looks at it after each step, finishes the outputs, writes a
// checkpoint and exits with 128 + the signal number (130, 143). A second signal of the
// same kind while the first is being handled ends the process at once (the default
// action), so a stuck run can still be killed with a second Ctrl-C.
namespace refmap {

/// Installs the handlers (idempotent).
void install_stop_handlers();
/// The signal that asked for a stop (SIGINT, SIGTERM), or 0.
int stop_requested();
/// Forgets a recorded signal (tests).
void clear_stop_request();

}  // namespace refmap
