// Sweeps: run a suite's cases into a folder, one result file per case written
// as it finishes (so a stopped sweep loses nothing and --resume skips what is
// done), then join the folder's results into results.json and the reports.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "harness/suite.h"

namespace sb {

struct SweepOptions {
  std::string suitePath;
  std::string out;
  std::string filter;  // regex on case ids; empty: all
  bool resume = false;
  int shardIndex = 1, shardCount = 1;  // --shard I/N, I in 1..N
  bool progressBar = false;            // a terminal: one updating line
  bool failFast = false;               // stop at the first failed case (else record it, go on)
};

// Runs the cases and writes the reports; returns the exit status: 0, or 1
// when an invariant failed (cases with "invariants": true) or a case failed (out
// of memory, a device error: recorded in its result file with the reason, and
// the sweep goes on unless failFast). Throws InputError for a bad suite, filter,
// shard or folder, and Interrupted when stopped (SIGINT, SIGTERM) between cases
// or inside one: what is done stays, and --resume continues.
int runSweep(const SweepOptions& o);

// Joins a sweep folder's cases into DIR/results.json and writes the reports.
// Returns the number of results.
int writeSweepReport(const std::string& dir);

// Copies the cases of shard folders (same suite) into a new folder `out`, then
// writes its reports. Throws InputError on a mismatch or a case in two inputs.
int mergeSweeps(const std::string& out, const std::vector<std::string>& inputs);

// "I/N" -> (I, N) with 1 <= I <= N.
std::pair<int, int> parseShard(const std::string& text);

// The machine and build a run was made on (date, commit, build type, compiler, CPU, OS).
nlohmann::json runContext();

}  // namespace sb
