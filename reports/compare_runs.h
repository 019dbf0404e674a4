// `strandbench compare-runs OLD NEW`: per-case timing changes between two runs, judged with a
// one-sided Mann-Whitney U test over the repetitions (see compare_runs.cpp for the rules).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace sb {

// The results of one run: a results.json, a sweep folder with results.json, or a sweep folder
// with only cases/*.json (one result object each, ordered by case.index).
struct RunResults {
  std::string source;                   // the file (or cases/ folder) the results came from
  nlohmann::json context;               // the run's context block; null when there is none
  std::vector<nlohmann::json> results;  // validated: case.id, frame_ms {median, samples?}, ...
};

// Throws InputError naming the path and the problem (missing, unreadable, not JSON, not the
// documented format, a case id twice).
RunResults loadRunResults(const std::string& path);

// How the cases' p-values are combined. A suite compares dozens of cases: at alpha 0.05 each,
// 38 unchanged cases give about two false SLOWER verdicts per comparison. Holm's step-down
// procedure keeps the chance of any false verdict among the cases (familywise) below alpha.
enum class Correction { None, Holm };

struct CompareRunsOptions {
  double thresholdPct = 5.0;  // a median must change by more than this to count
  double alpha = 0.05;        // significance level of the one-sided test
  Correction correction = Correction::Holm;
};

enum class Verdict { Ok, Slower, Faster, NotJudged, DefinitionChanged, Added, Removed };
const char* verdictName(Verdict v);  // "ok", "SLOWER", "faster", "not judged", ...

// One timing (a case's frame_ms, or one pass's ms) in both runs.
struct TimingChange {
  std::string name;  // case id, or pass name
  Verdict verdict = Verdict::NotJudged;
  std::string note;  // why not judged, or extra information
  std::optional<double> oldMedian, newMedian, changePct;
  // One-sided p-value in the direction of the median change (new slower when changePct >= 0,
  // new faster otherwise); absent when not judged.
  std::optional<double> p;
  // p after Holm's correction over the run's judged cases (frames only; passes are information).
  std::optional<double> pAdjusted;
  bool exact = false;  // p from the exact distribution (else the normal approximation)
  int oldSamples = 0, newSamples = 0;
};

// Judges one timing object ({median, samples, ...}) of each run.
TimingChange compareTiming(const nlohmann::json& oldMs, const nlohmann::json& newMs,
                           const CompareRunsOptions& options);

struct CaseComparison {
  std::string id;
  Verdict verdict = Verdict::Ok;  // the frame's verdict, or DefinitionChanged, Added, Removed
  TimingChange frame;
  // Passes that slowed or sped up beyond the threshold with significance, and passes only in
  // one of the runs (Added / Removed). Information only: the case's verdict is the frame's.
  std::vector<TimingChange> passes;
};

// Cases in OLD's order, then the cases only in NEW in NEW's order.
std::vector<CaseComparison> compareRuns(const RunResults& oldRun, const RunResults& newRun,
                                        const CompareRunsOptions& options);

// Paired runs: olds[i] and news[i] were taken one after the other (alternating which went
// first), so the machine's drift over the rounds affects both alike. Per case, the ratios
// new_i/old_i of the frame medians are judged with a one-sided Wilcoxon signed-rank test of
// their logarithms (p from signedRankGreater); change = median ratio - 1; old and new median
// are the medians of the rounds' medians. The verdicts follow the same threshold and alpha as
// compareRuns; with too few pairs to reach alpha (2^-n >= alpha: 4 pairs at 0.05) a case is
// not judged. A case missing from any run, or defined differently than in the first pair, is
// added, removed or definition changed as in compareRuns. Passes are not listed.
std::vector<CaseComparison> comparePairedRuns(const std::vector<RunResults>& olds,
                                              const std::vector<RunResults>& news,
                                              const CompareRunsOptions& options);

// Holm's step-down correction over the frame p-values of the judged cases: each case's verdict
// is decided again with its adjusted p (threshold unchanged). No-op with Correction::None.
void applyCorrection(std::vector<CaseComparison>& cases, const CompareRunsOptions& options);

// Prints the table (or one JSON object with asJson) and returns the exit status: 1 when a case
// is Slower, else 0. With morePairs, OLD NEW is the first of several paired runs
// (comparePairedRuns). Throws InputError for bad input or options.
int runCompareRuns(const std::string& oldPath, const std::string& newPath,
                   const CompareRunsOptions& options, bool asJson, std::ostream& out,
                   const std::vector<std::pair<std::string, std::string>>& morePairs = {});

}  // namespace sb
