#include "harness/stop.h"

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>

#include "base/errors.h"

namespace sb {
namespace {

volatile std::sig_atomic_t gStop = 0;
bool gProgressLines = true;

extern "C" void onStopSignal(int sig) { gStop = sig; }

// Off a terminal, a line at most this often: a log of an overnight run stays short.
constexpr double kPlainProgressSeconds = 5.0;

double plainProgressSeconds() {
  const char* s = std::getenv("SB_PROGRESS_SECONDS");
  char* end = nullptr;
  const double v = s ? std::strtod(s, &end) : -1.0;
  return s && *s && *end == '\0' && v >= 0.0 ? v : kPlainProgressSeconds;
}

}  // namespace

void installStopHandlers() {
  struct sigaction sa {};
  sa.sa_handler = onStopSignal;
  sigemptyset(&sa.sa_mask);
  // No SA_RESTART needed: the work polls the flag. SA_RESETHAND puts the
  // default back, so a second Ctrl-C ends a stuck pass at once.
  sa.sa_flags = SA_RESETHAND;
  ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);
}

int stopSignal() { return gStop; }

void throwIfStopped() {
  if (gStop != 0) throw Interrupted(gStop);
}

void clearStop() { gStop = 0; }

void ProgressLine::enable(bool on) { gProgressLines = on; }

ProgressLine::ProgressLine(std::string what)
    : what_(std::move(what)),
      enabled_(gProgressLines),
      terminal_(::isatty(STDERR_FILENO) != 0),
      plainSeconds_(terminal_ ? 0.0 : plainProgressSeconds()),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

ProgressLine::~ProgressLine() {
  if (shown_ && terminal_) std::fprintf(stderr, "\r\033[K");
}

void ProgressLine::update(const std::string& text) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (!terminal_) {
    // A plain line each plainSeconds_, the first after as long (short work shows nothing).
    if (std::chrono::duration<double>(now - last_).count() < plainSeconds_) return;
    last_ = now;
    std::fprintf(stderr, "%s: %s, %.0f s\n", what_.c_str(), text.c_str(), elapsed);
    std::fflush(stderr);
    return;
  }
  // Short work shows nothing; a shown line is redrawn at most 5 times a second.
  if (elapsed < 2.0 || (shown_ && now - last_ < std::chrono::milliseconds(200))) return;
  last_ = now;
  shown_ = true;
  std::fprintf(stderr, "\r\033[K%s: %s, %.0f s", what_.c_str(), text.c_str(), elapsed);
  std::fflush(stderr);
}

}  // namespace sb
