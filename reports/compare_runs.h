// `strandbench compare-runs OLD NEW`: per-case work changes between two runs, judged exactly
// from the work counters, and timing changes, judged with a one-sided Mann-Whitney U test over
// the repetitions (see compare_runs.cpp for the rules).
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
  std::string suite;                    // the suite's name ("" when the run does not say)
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
  bool failOnWorkChange = false;  // exit status 1 on a work change too (else it only shows)
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

// ---- work: the exact counters of passes[].work ----

// One counter of one pass. For a pass in only one run, the value it has there (the other
// absent).
struct CounterChange {
  std::string counter;  // vertices, fragment_invocations, bytes_written, ...
  std::optional<double> oldValue, newValue;
  std::optional<double> ratio() const;      // new/old, absent when old is 0 or absent
  std::optional<double> changePct() const;  // (new - old)/old * 100, likewise
};

enum class PassWorkKind { Changed, Added, Removed };
const char* passWorkKindName(PassWorkKind k);  // "changed", "added", "removed"

struct PassWorkChange {
  std::string pass;  // its name
  PassWorkKind kind = PassWorkKind::Changed;
  // Changed: the counters that differ. Added / removed: every counter the pass has.
  std::vector<CounterChange> counters;
};

enum class WorkStatus { Same, Changed, NotCounted, NotCompared };
const char* workStatusName(WorkStatus s);  // "same", "changed", "not counted", "not compared"

struct WorkComparison {
  WorkStatus status = WorkStatus::NotCompared;
  std::string note;                    // why not counted / not compared
  std::vector<PassWorkChange> passes;  // Changed only
  std::size_t counterCount() const;    // counters over all passes
};

// The settings that define what a case measures (scene.spec, shadow, oit, size, primitive),
// each that differs as "name old -> new": its timings and work are then incomparable.
std::vector<std::string> definitionChanges(const nlohmann::json& oldResult,
                                           const nlohmann::json& newResult);

// Compares the work of one case in two runs (both result objects, the same definition).
// Counters are exact, so any difference is a change: no threshold, no test. Passes are matched
// by name (the k-th pass of a name with the k-th). NotCounted when either result has no work
// (frame_work, or work in any pass: runs from before the counters existed). A counter null or
// absent in either pass (samples_passed without device queries) is not compared; `resources`
// is not a counter (its bytes are in bytes_written, bytes_read, bytes_storage).
WorkComparison compareWork(const nlohmann::json& oldResult, const nlohmann::json& newResult);

// One line per pass: "pass NAME added: vertices 30000, ..." or "pass NAME: fragment_invocations
// 100 -> 200 (x2, +100%)".
std::string describeWorkChange(const PassWorkChange& p);
nlohmann::json workChangesJson(const std::vector<PassWorkChange>& passes);

struct CaseComparison {
  std::string id;
  Verdict verdict = Verdict::Ok;  // the frame's verdict, or DefinitionChanged, Added, Removed
  TimingChange frame;
  // Passes that slowed or sped up beyond the threshold with significance, and passes only in
  // one of the runs (Added / Removed). Information only: the case's verdict is the frame's.
  std::vector<TimingChange> passes;
  // Exact work counters, judged apart from the timings (NotCompared for added, removed and
  // redefined cases).
  WorkComparison work;
};

// Cases in OLD's order, then the cases only in NEW in NEW's order; each with its timing verdict
// and its work comparison.
std::vector<CaseComparison> compareRuns(const RunResults& oldRun, const RunResults& newRun,
                                        const CompareRunsOptions& options);

// Paired runs: olds[i] and news[i] were taken one after the other (alternating which went
// first), so the machine's drift over the rounds affects both alike. Per case, the ratios
// new_i/old_i of the frame medians are judged with a one-sided Wilcoxon signed-rank test of
// their logarithms (p from signedRankGreater); change = median ratio - 1; old and new median
// are the medians of the rounds' medians. The verdicts follow the same threshold and alpha as
// compareRuns; with too few pairs to reach alpha (2^-n >= alpha: 4 pairs at 0.05) a case is
// not judged. A case missing from any run, or defined differently than in the first pair, is
// added, removed or definition changed as in compareRuns. Passes are not listed. Work is
// compared between the first pair (counters are exact: every round counts the same).
std::vector<CaseComparison> comparePairedRuns(const std::vector<RunResults>& olds,
                                              const std::vector<RunResults>& news,
                                              const CompareRunsOptions& options);

// Holm's step-down correction over the frame p-values of the judged cases: each case's verdict
// is decided again with its adjusted p (threshold unchanged). No-op with Correction::None.
void applyCorrection(std::vector<CaseComparison>& cases, const CompareRunsOptions& options);

// How much two runs have in common: the cases in both (by case.id), and a warning when they
// are runs of different suites or share less than half of the larger run's cases (their
// comparison is mostly cases added and removed). Throws InputError when they share no case:
// nothing can be compared.
struct RunOverlap {
  std::size_t shared = 0;
  std::vector<std::string> warnings;
};
RunOverlap runOverlap(const RunResults& oldRun, const RunResults& newRun);

// Prints the work changes and the timing table (or one JSON object with asJson) and returns the
// exit status: 1 when a case is Slower, or (with failOnWorkChange) when work changed, else 0;
// runs that share no case are refused (InputError); a small overlap only warns. With
// morePairs, OLD NEW is the first of several paired runs (comparePairedRuns). Throws InputError for
// bad input or options.
int runCompareRuns(const std::string& oldPath, const std::string& newPath,
                   const CompareRunsOptions& options, bool asJson, std::ostream& out,
                   const std::vector<std::pair<std::string, std::string>>& morePairs = {});

}  // namespace sb
