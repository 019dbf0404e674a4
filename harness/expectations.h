// Per-driver expectations for `strandbench check`, as Mesa's CI keeps them for
// deqp-runner: the comparisons known to fail on a driver, the ones known to be
// flaky, and the ones skipped, each with the reason.
//
// File: <baselines>/expectations/<driver>.json (or `check --expectations FILE`):
//   {
//     "comment": "...",                       // optional
//     "driver": "mesa-25.0",                  // the driver it describes
//     "failures": [ {"case": "fur-lines-shadowmap", "comparison": "gl",
//                    "reason": "why it differs and which driver is nearer the truth"}, ... ],
//     "flakes":   [ ... ],                    // may fail or pass: either is fine
//     "skips":    [ ... ]                     // not rendered (or not compared)
//   }
// "case" names a case of the manifest exactly; "comparison" is one of its comparisons
// ("gl", "vulkan", "gl-vs-vulkan"), or absent for all of them; "reason" is required.
// A skipped backend is not rendered, and its comparison against the first backend is
// skipped with it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "harness/baselines.h"

namespace sb {

struct Expectation {
  std::string caseName;
  std::string comparison;  // empty: every comparison of the case
  std::string reason;
  bool matches(const std::string& name, const std::string& label) const;
};

struct Expectations {
  std::filesystem::path file;  // empty: none (every comparison is expected to pass)
  std::string driver;
  std::vector<Expectation> failures, flakes, skips;

  // The entry of `list` for this comparison, or null.
  static const Expectation* find(const std::vector<Expectation>& list, const std::string& name,
                                 const std::string& label);
};

// The driver's name as expectation files and per-driver baselines use it: "system",
// a name under drivers/, or the folder name of a driver given by path.
std::string driverKey(const std::string& driver);

// <baselines>/expectations/<driverKey>.json
std::filesystem::path expectationsFile(const std::filesystem::path& baselines,
                                       const std::string& driver);

// Reads and checks a file against the manifest: every case must exist, every
// comparison must be one the case makes, every entry must give a reason, and no
// comparison may be listed twice. Throws InputError naming the file and the entry.
Expectations loadExpectations(const std::filesystem::path& file, const Manifest& m);

}  // namespace sb
