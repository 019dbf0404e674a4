// The error kinds that cross folders: thrown in scenes/, backends/, reports/ and
// harness/, and caught by the harness, which turns them into exit statuses (2 for
// bad input or an unavailable backend; cli/commands.h, runGuarded). They live
// here, header-only and with no dependencies, so that every library can throw them
// without linking another (the fuzz build compiles scenes/ alone).
#pragma once

#include <csignal>
#include <stdexcept>
#include <string>
#include <utility>

namespace sb {

// Bad input from the user (a file, a spec, an option): the CLI prints the
// message and exits with status 2. The message names the file/option and the problem.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Input that names an optional part this machine lacks (a driver scripts/drivers.sh has not
// fetched, ray queries the device does not offer): bad input for one run (exit 2), a case
// not run in a sweep (harness/sweep.h). `enable` says what provides the part.
struct UnavailableError : InputError {
  UnavailableError(const std::string& what, std::string how)
      : InputError(what), enable(std::move(how)) {}
  std::string enable;
};

// Any failure of a backend (no device, shader compile error, API error).
struct DeviceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Memory that is not there: a run over --memory-limit or the device's budget
// (refused before its resources are made), or an allocation that failed anyway
// (host std::bad_alloc, VK_ERROR_OUT_OF_*_MEMORY, GL_OUT_OF_MEMORY). The message
// names what was being allocated and its size. A DeviceError, so that every
// caller that handles device failures (exit 2, a sweep's failed case) handles it.
struct OutOfMemoryError : DeviceError {
  using DeviceError::DeviceError;
};

// A stop asked for by SIGINT or SIGTERM (harness/stop.h), thrown between
// passes, frames and cases so that destructors remove partial files. Not an
// error of the run: the CLI exits with 128 + the signal number.
struct Interrupted : std::runtime_error {
  explicit Interrupted(int sig)
      : std::runtime_error(sig == SIGINT ? "stopped by SIGINT" : "stopped by SIGTERM"),
        signal(sig) {}
  int signal;
};

}  // namespace sb
