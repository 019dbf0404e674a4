// Measurements that hold on a noisy machine: the repetitions of a group of cases are taken in
// rounds, round-robin (round r runs every case once, starting at case r mod n), so a slow drift
// of the machine (another job, thermal limits, a frequency change) hits every case alike instead
// of the cases that happened to run during it; the count of rounds adapts until every case's
// median is known to a target precision; medians and ratios carry bootstrap 95% intervals;
// outliers are marked, not dropped. Used by bench-shadows and bench-oit; a benchmark's row
// calls printRatio to print a ratio with its interval and the paper's ordering verdict.
#pragma once

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "reports/stats.h"

namespace sb {

// The rounds of a run, resolved (run_options.h: repetitions() from the options given).
struct RepetitionOptions {
  int minReps = 5;         // rounds always taken
  int maxReps = 15;        // rounds at most
  double targetCiPct = 0;  // stop once every median's 95% interval is within +-PCT (0: minReps)
};

// One case's samples (one per round, in round order) with their median's interval and the
// samples Tukey's fences mark as outliers.
struct Measurement {
  std::vector<double> samples;
  Interval median;
  std::vector<bool> outliers;
  int outlierCount() const;
};

// Runs cases[i]() once per round (each call returns one sample, e.g. a frame time in ms) until
// minReps rounds are done and every median's interval is within targetCiPct, or maxReps.
// A case that returns NaN (it failed) is left out of the later rounds and of the target; its
// samples are the ones before. Throws InputError for too few rounds (naming --min-reps); the
// options' ranges are checked where they are read (harness/run_options.h).
std::vector<Measurement> measureInterleaved(const std::vector<std::function<double()>>& cases,
                                            const RepetitionOptions& options, int leastMinReps = 2);
// leastMinReps: 2 where an interval is always printed (the benchmarks); a sweep allows 1.
void checkRepetitionOptions(const RepetitionOptions& options, int leastMinReps = 2);
// --max-reps below --min-reps: InputError (the one message, for given and resolved rounds).
void checkRepetitionOrder(int minReps, int maxReps);

// The ratio of two cases' medians with a paired bootstrap 95% interval (the rounds resampled
// together: both samples of a round saw the same state of the machine).
Interval ratioInterval(const Measurement& num, const Measurement& den);

// Rounds below which printRatio judges no ordering (the interval is printed, "undecided").
inline constexpr std::size_t kMinRoundsForVerdict = 5;

// A paper's claimed ordering of a ratio: below `bound` (claimBelow) or above it.
struct OrderingClaim {
  double bound = 1.0;
  bool claimBelow = true;
  std::string text;  // "DOM(3) faster than OSM(16)"
};

// "  LABEL: 0.60 [0.57, 0.63]  (PAPER)" and, with a claim, "    paper's ordering (TEXT): holds
// with 95% confidence | fails with 95% confidence | undecided (the interval contains BOUND)".
// Returns the interval.
Interval printRatio(std::ostream& out, const std::string& label, const Measurement& num,
                    const Measurement& den, const std::string& paper,
                    const std::optional<OrderingClaim>& claim = std::nullopt);

// " 12.34 ms [12.1, 12.6], 7 reps, 1 outlier": a measurement for a benchmark's row.
std::string describe(const Measurement& m);

// The machine's state around a benchmark: "load 0.52 0.61 0.70, governor performance".
std::string machineState();

}  // namespace sb
