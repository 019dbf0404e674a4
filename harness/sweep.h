// Sweeps: run a suite's cases into a folder, one result file per case written
// as it finishes (so a stopped sweep loses nothing and --resume skips what is
// done), then join the folder's results into results.json and the reports.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "harness/run_context.h"
#include "harness/run_options.h"
#include "harness/suite.h"

namespace sb {

struct SweepOptions {
  std::string suitePath;
  std::string out;
  // The folder the messages name, where the sweep writes into a temporary one that is
  // renamed to it afterwards (figure); empty: out.
  std::string shownOut;
  std::string filter;  // regex on case ids; empty: all
  bool resume = false;
  int shardIndex = 1, shardCount = 1;  // --shard I/N, I in 1..N
  std::string shardSource;             // where --shard auto found it ("SLURM_ARRAY_TASK_ID")
  bool progressBar = false;            // a terminal: one updating line
  bool failFast = false;               // stop at the first failed case (else record it, go on)
  // A case that needs a part this machine lacks (a driver not installed, ray queries the device
  // does not offer) is not run: recorded with the reason and what provides the part, listed at
  // the end. It fails the sweep (exit 1) only with requireParts (--require-drivers, CI=true).
  bool requireParts = false;
  // Timing (harness/measure.h): a group's cases are measured in interleaved rounds, each
  // round rendering every case of the group once (a fresh device, its warm-up frames, one
  // timed frame); the first round also makes the case's images and errors. Back to back
  // (interleave false): one run of each case with its `repeat` frames, as `render` does.
  bool interleave = true;
  RunOptions rounds;  // --min-reps (0: the group's largest `repeat`), --max-reps, --target-ci
  // Every case of the sweep in one interleaved run, not one run per group (figure: its paper
  // tables compare cases of different groups, and a time verdict needs one interleaved run).
  bool interleaveAcrossGroups = false;
  // The shared case store (harness/case_store.h; empty: none): a case it holds for the same
  // key is taken from it, not run; a case measured here is kept in it.
  std::string cases;
  // Cases on another driver than the process's ("drivers" in the suite) run in a child
  // sweep per driver, started with --driver D and this set: it runs only the cases of its
  // own driver and leaves the reports to the parent.
  bool driverCasesOnly = false;
};

// Runs the cases and writes the reports; returns the exit status: 0, or 1
// when an invariant failed (cases with "invariants": true) or a case failed (out
// of memory, a device error, input only a run finds bad: recorded in its result file
// with the reason, and the sweep goes on unless failFast), or, with requireParts, a case
// was not run for a missing part. Throws InputError for a bad suite, filter, shard or
// folder, or a file a case names that is missing or broken (all checked before anything
// runs or is written), and Interrupted when stopped (SIGINT, SIGTERM) between cases or
// inside one: every finished case stays (a case of an interleaved group whose first round
// is done is kept with the rounds it had, marked in its measurement), the files of the
// unfinished ones are removed, and --resume runs only the cases not kept.
int runSweep(const SweepOptions& o);

// Joins a sweep folder's cases into DIR/results.json and writes the reports.
// Returns the number of results.
int writeSweepReport(const std::string& dir);

// What `merge` found: the results written (0 when refused), and what is missing: the
// shards (1-based indices of N, from the shards' sweep.json) and the cases of the suite that
// no input holds.
struct MergeOutcome {
  int results = 0;
  bool written = false;
  int shardCount = 0;
  std::vector<int> missingShards;
  std::vector<std::string> missingCases;
};

// Copies the cases of shard folders (same suite) into a new folder `out`, then writes its
// reports; the merged context keeps each shard's context (host, devices, drivers) under
// "shards". Throws InputError on a mismatch or a case in two inputs. When a shard or case is
// missing nothing is written unless allowMissing (then the context lists what is missing).
MergeOutcome mergeSweeps(const std::string& out, const std::vector<std::string>& inputs,
                         bool allowMissing = false);

}  // namespace sb
