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

// Progress of long work on stderr (never stdout: its JSON stays clean). On a
// terminal: one line rewritten in place once the work has taken about two
// seconds, cleared when done. Off a terminal (a log, a pipe, a batch job): a
// plain line every few seconds (kPlainProgressSeconds; SB_PROGRESS_SECONDS=S
// sets it, 0: every update), so a long run never looks hung.
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
  bool enabled_ = false, terminal_ = false, shown_ = false;
  double plainSeconds_ = 0;  // off a terminal: the least time between two lines
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace sb
