#include "harness/run_options.h"

#include <algorithm>

namespace sb {

namespace {
constexpr int kMostReps = 100000;
constexpr int kTargetDefaultMaxReps = 15;  // rounds at most when a target is given alone
}  // namespace

const OptionTable<RunOptions>& runOptionTable() {
  using R = RunOptions;
  static const OptionTable<R> table(
      {opt::integer(&R::minReps, "min-reps", 0, 0, kMostReps,
                    "rounds always taken (each renders every case once); 0: the default"),
       opt::integer(&R::maxReps, "max-reps", 0, 0, kMostReps,
                    "rounds at most; 0: --min-reps, or 15 with --target-ci"),
       opt::number(&R::targetCiPct, "target-ci", "0", 0, 100,
                   "PCT: take rounds until every median's 95% interval is within +-PCT of it (or "
                   "--max-reps); 0: --min-reps rounds")},
      [](R& o) {
        if (o.minReps && o.maxReps) checkRepetitionOrder(o.minReps, o.maxReps);
      });
  return table;
}

RepetitionOptions repetitions(const RunOptions& o, int defaultMinReps) {
  RepetitionOptions r;
  r.minReps =
      o.minReps ? o.minReps : (o.maxReps ? std::min(defaultMinReps, o.maxReps) : defaultMinReps);
  r.maxReps = o.maxReps
                  ? o.maxReps
                  : (o.targetCiPct > 0 ? std::max(r.minReps, kTargetDefaultMaxReps) : r.minReps);
  r.targetCiPct = o.targetCiPct;
  return r;
}

std::vector<std::string> runOptionArguments(const RunOptions& o) {
  std::vector<std::string> args;
  for (const auto& [name, text] : runOptionTable().given(o)) {
    args.push_back("--" + name);
    args.push_back(text);
  }
  return args;
}

int childStatus(int status, const std::string& who, const std::function<void()>& onStop) {
  if (status == 130 || status == 143) {
    if (onStop) onStop();
    throw Interrupted(status == 130 ? 2 : 15);
  }
  if (status == 2) throw InputError(who + " refused its input");
  return status;
}

CliRunOptions::CliRunOptions(CLI::App& cmd, const std::string& defaults)
    : given_(std::make_shared<std::map<std::string, std::string>>()) {
  for (const OptionInfo& info : runOptionTable().infos()) {
    const std::string help =
        info.name == "min-reps" ? info.help + " (" + defaults + ")" : info.help;
    auto given = given_;
    cmd.add_option_function<std::string>(
        "--" + info.name, [given, name = info.name](const std::string& v) { (*given)[name] = v; },
        help);
  }
}

RunOptions CliRunOptions::read() const {
  Spec spec;
  spec.options = *given_;
  return runOptionTable().read(spec, "run options");
}

}  // namespace sb
