// `strandbench history`: a case's timing over many runs (nightly sweeps), with change points
// found by a stated test, written as history.json and an offline history.html; a newest-run
// slowdown is an alarm (exit status 1).
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "reports/compare_runs.h"
#include "reports/stats.h"

namespace sb {

struct HistoryOptions {
  double thresholdPct = 5.0;  // a slowdown must be larger than this to alarm
  double alpha = 0.01;        // the change-point test's level (its false-alarm rate per case)
  int recent = 10;            // an alarm when the slowdown starts within the newest runs
  int permutations = 999;     // of the permutation test
};

struct HistoryPoint {
  std::string run;   // the run's source (path)
  std::string date;  // its context.date
  Interval median;   // frame_ms median with its bootstrap 95% interval over the repetitions
  int samples = 0;
};

// A run where a case's work counters differ from the previous run that had the case.
struct WorkStep {
  int index = 0;  // into points: the first run with the new work
  std::vector<PassWorkChange> passes;
};

struct CaseHistory {
  std::string id;
  std::vector<HistoryPoint> points;  // one per run that has the case, oldest first
  // Exact, apart from the timings' change points: every run whose work differs from the
  // previous run's (compareWork; runs without work, and redefined cases, are not compared).
  std::vector<WorkStep> workChanges;
  std::vector<ChangePoint> changes;  // indices into points
  bool alarm = false;
  std::string verdict;  // one line: the latest change, or "no change"
  // The size of the latest change (after/before - 1), 0 without one: the sort key.
  double latestChange() const { return changes.empty() ? 0.0 : changes.back().size; }
};

struct History {
  std::vector<std::string> runs;   // oldest first
  std::vector<CaseHistory> cases;  // sorted by |latest change|, largest first
  int alarms = 0;
  int workChanged = 0;  // cases with at least one work change
};

// The cases of the runs (already in date order) over time: the median of frame_ms per run with
// its interval, change points on the series of medians (findChangePoints at options.alpha),
// and the alarm: the latest change point is a slowdown larger than thresholdPct that starts
// within the newest `recent` runs. Work changes between consecutive runs are listed per case;
// they never alarm (as compare-runs, a change of work is often intended).
History buildHistory(const std::vector<RunResults>& runs, const HistoryOptions& options);

nlohmann::json historyJson(const History& history, const HistoryOptions& options);
// A page without scripts or external resources: one small chart per case (medians with their
// intervals, change points marked), cases sorted by the size of their latest change.
std::string historyHtml(const History& history, const HistoryOptions& options);

// Loads the runs (each a sweep folder or results.json; a folder holding run folders stands for
// all of them), orders them by context.date, writes OUT/history.json and OUT/history.html and
// prints a summary that opens with the work changes and then the time changes. Returns 1 when
// a case alarms, else 0. Throws InputError for bad input.
int runHistory(const std::vector<std::string>& paths, const std::string& out,
               const HistoryOptions& options, std::ostream& log);

}  // namespace sb
