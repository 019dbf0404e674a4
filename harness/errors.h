// The error kinds that cross folders: thrown in scenes/, backends/, reports/ and
// harness/, and caught by the harness, which turns them into exit statuses (2 for
// bad input or an unavailable backend; harness/commands.h, runGuarded). They live
// here, header-only and with no dependencies, so that every library can throw them
// without linking another (the fuzz build compiles scenes/ alone).
#pragma once

#include <stdexcept>

namespace sb {

// Bad input from the user (a file, a spec, an option): the CLI prints the
// message and exits with status 2. The message names the file/option and the problem.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Any failure of a backend (no device, shader compile error, API error).
struct DeviceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace sb
