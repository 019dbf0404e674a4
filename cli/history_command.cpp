// `strandbench history`: the command line over runHistory (reports/history.h).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "reports/history.h"

namespace sb {

void registerHistoryCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "history",
      "each case's work and frame time over many runs, with change points; exit 1 on a new "
      "slowdown");
  auto paths = std::make_shared<std::vector<std::string>>();
  auto out = std::make_shared<std::string>();
  auto o = std::make_shared<HistoryOptions>();
  cmd->add_option("RUNS", *paths,
                  "runs (sweep folders or results.json), or a folder of run folders; ordered "
                  "by their context.date")
      ->required();
  cmd->add_option("--out", *out, "folder for history.json and history.html")->required();
  cmd->add_option("--threshold", o->thresholdPct,
                  "percent a slowdown must exceed to raise the alarm")
      ->capture_default_str();
  cmd->add_option("--alpha", o->alpha,
                  "level of the change-point test: the chance of a false change per case")
      ->capture_default_str();
  cmd->add_option("--recent", o->recent,
                  "alarm when the latest slowdown starts within this many newest runs")
      ->capture_default_str();
  cmd->footer(
      "The summary and history.html open with 'work changed' and 'time changed'.\n"
      "Work: per case, every run whose work counters (passes[].work) differ from the previous\n"
      "run's, naming the pass and counter with old and new value, or a pass added or removed.\n"
      "Counters are exact, so any difference is listed; runs without work and redefined cases\n"
      "are not compared. A work change is information: it never raises the alarm.\n"
      "Time, per case and run: the frame_ms median with its 95% percentile-bootstrap interval over "
      "the\n"
      "run's repetitions (frame_ms.samples). Change points in the series of medians: binary\n"
      "segmentation; each segment is split where Pettitt's rank statistic (the Mann-Whitney\n"
      "statistic of the split, standardized) is largest, when its permutation p-value (999\n"
      "shuffles) is below --alpha. On a series without a change this reports one with chance\n"
      "at most --alpha. A change needs a few runs on each side to be significant (at least 2;\n"
      "about 5 for a 10% step in 5% noise), so a slowdown is flagged when the newest runs\n"
      "confirm it: exit 1 when a case's latest change point is a slowdown larger than\n"
      "--threshold percent that starts within the newest --recent runs. Exit 0 otherwise, 2 on\n"
      "bad input.");
  cmd->callback(
      [=] { runGuarded("history", [&] { return runHistory(*paths, *out, *o, std::cout); }); });
}

}  // namespace sb
