// The run options of the timed commands (bench, sweep, figure): --min-reps, --max-reps and
// --target-ci, declared once in an OptionTable (base/options.h) with their ranges and the rule
// between them; the CLI options come from it (CliRunOptions), and so do the arguments a child
// process is given to read the same options (runOptionArguments).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "base/options.h"
#include "harness/measure.h"

namespace sb {

// As given; 0: the command's default.
struct RunOptions {
  int minReps = 0;         // rounds always taken
  int maxReps = 0;         // rounds at most
  double targetCiPct = 0;  // take rounds until every median's 95% interval is within +-PCT
};

// min-reps, max-reps, target-ci (the CLI spells them --min-reps, ...).
const OptionTable<RunOptions>& runOptionTable();

// The rounds a run takes: minReps (default: defaultMinReps, at most maxReps), maxReps
// (default: minReps, or 15 with a target), the target.
RepetitionOptions repetitions(const RunOptions& o, int defaultMinReps);

// The options not at their defaults as a child's arguments: {"--min-reps", "3", ...}.
std::vector<std::string> runOptionArguments(const RunOptions& o);

// A child strandbench's exit status as the parent's outcome: 130 and 143 (SIGINT, SIGTERM)
// throw Interrupted after `onStop`, 2 throws InputError "<who> refused its input"; any other
// status is returned.
int childStatus(int status, const std::string& who, const std::function<void()>& onStop = {});

// The run options as CLI options of `cmd`; read() checks them after parsing (InputError:
// exit status 2). `defaults` is added to --min-reps' help: the command's default rounds.
class CliRunOptions {
 public:
  CliRunOptions(CLI::App& cmd, const std::string& defaults);
  RunOptions read() const;

 private:
  std::shared_ptr<std::map<std::string, std::string>> given_;
};

}  // namespace sb
