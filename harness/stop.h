// Clean stops and progress for long work. SIGINT and SIGTERM only set a flag
// (the handler does nothing else); the work checks it between passes, frames,
// cases and baselines (throwIfStopped throws Interrupted), so destructors and
// temporary files clean up and nothing is left half written. The CLI exits with
// 128 + the signal number: 130 for SIGINT, 143 for SIGTERM.
#pragma once

#include <chrono>
#include <string>

namespace sb {

// Installs the handlers (once; SA_RESETHAND: a second signal stops at once).
void installStopHandlers();
// The signal that asked for a stop, or 0.
int stopSignal();
// Throws Interrupted when a stop was asked for.
void throwIfStopped();
// For tests: forget a stop asked for earlier.
void clearStop();

// One line on stderr, rewritten in place, for work that has taken more than
// about two seconds, and only when stderr is a terminal (off a terminal it
// prints nothing, so stdout's JSON and logs stay clean). Cleared when done.
class ProgressLine {
 public:
  // Off while a caller draws its own line on the terminal (the sweep's bar).
  static void enable(bool on);

  explicit ProgressLine(std::string what);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;
  // The current state ("frame 2/10, pass 812/1641 peel.step"); printed at most
  // a few times a second.
  void update(const std::string& text);

 private:
  std::string what_;
  bool enabled_ = false, shown_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace sb
