// `strandbench compare-runs`: the command line over runCompareRuns (reports/compare_runs.h).
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "base/errors.h"
#include "cli/commands.h"
#include "reports/compare_runs.h"

namespace sb {

void registerCompareRunsCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "compare-runs",
      "compare the work and the timings of two runs case by case (exit 1 when a case slowed "
      "significantly)");
  auto oldPath = std::make_shared<std::string>();
  auto newPath = std::make_shared<std::string>();
  auto threshold = std::make_shared<std::string>("5");
  auto alpha = std::make_shared<double>(0.05);
  auto asJson = std::make_shared<bool>(false);
  auto correction = std::make_shared<std::string>("holm");
  auto pairs = std::make_shared<std::vector<std::string>>();
  auto failOnWork = std::make_shared<bool>(false);
  cmd->add_option("OLD", *oldPath, "results.json, or a sweep folder (results.json or cases/*.json)")
      ->required();
  cmd->add_option("NEW", *newPath, "the same, for the run to judge")->required();
  cmd->add_option("--threshold", *threshold,
                  "percent a median must change by to count (e.g. 5 or 5%)")
      ->capture_default_str();
  cmd->add_option("--alpha", *alpha, "significance level of the one-sided test")
      ->capture_default_str();
  cmd->add_option("--correction", *correction,
                  "holm: alpha bounds the chance of any false verdict among the cases (Holm's "
                  "step-down); none: alpha per case")
      ->check(CLI::IsMember({"holm", "none"}))
      ->capture_default_str();
  cmd->add_flag("--json", *asJson, "print one JSON object instead of the table");
  cmd->add_flag("--fail-on-work-change", *failOnWork,
                "exit 1 when any work counter changed (by default a work change only shows)");
  cmd->add_option("--pair", *pairs,
                  "OLD NEW: one more pair of runs taken one after the other; OLD NEW and every "
                  "--pair are then judged as paired rounds (repeat the option)")
      ->expected(2)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->footer(
      "The output opens with two lines: 'work changed' and 'time changed'.\n"
      "Work (passes[].work: vertices, primitives, fragment_invocations, draws, bytes_written, "
      "...)\n"
      "is exact: a case counts the same every time it runs, so any difference in any counter of\n"
      "any pass, and a pass in only one run, is a work change, listed with the pass, counter, old\n"
      "and new value and their ratio; no threshold, no test. A work change does not fail the\n"
      "comparison (exit 0) unless --fail-on-work-change is given: it is often what a commit\n"
      "meant to do, and it shows in the first line either way. Results without work (older runs)\n"
      "are 'not counted'; counters null in either run (samples_passed without device queries)\n"
      "are not compared, nor are cases added, removed or redefined.\n"
      "Cases are matched by case.id; cases in only one run are listed as added/removed and do not\n"
      "fail. Runs of different suites, or that share less than half of the larger run's cases,\n"
      "get a 'warning:' line (the exit status is unchanged); runs that share no case are refused\n"
      "(exit 2). A case whose scene, shadow, oit, size or primitive differ is 'definition changed' "
      "and\n"
      "is not judged. For the rest, change = new/old frame_ms median - 1, and the repetitions\n"
      "(frame_ms.samples) get a one-sided Mann-Whitney U test in the direction of the change\n"
      "(exact distribution without ties and m*n <= 2500, else the normal approximation with tie\n"
      "and continuity correction); p is that test's p-value.\n"
      "  SLOWER  change > +threshold and p < alpha (a regression: exit status 1)\n"
      "  faster  change < -threshold and p < alpha (information)\n"
      "  ok      otherwise ('not significant' when the change alone is beyond the threshold)\n"
      "  not judged: 'no samples' (a run lacks frame_ms.samples: summary statistics cannot be\n"
      "  tested), or 'too few repetitions' (1/C(m+n,m) >= alpha: even fully separated samples\n"
      "  could not be significant; at alpha 0.05, 3 vs 3 is too few, 4 vs 4 is enough).\n"
      "Over the cases, p is corrected by Holm's step-down procedure (--correction holm, the\n"
      "default): with 38 unchanged cases at alpha 0.05 each, about two would be SLOWER by chance\n"
      "in every comparison; corrected, the chance of any false verdict is at most alpha. The\n"
      "verdicts use the corrected p ('p Holm'); --correction none judges each case alone.\n"
      "Passes that are slower or faster by the same rules, or in only one run, are listed under\n"
      "their case for information (only the frame time fails a case).\n"
      "With --pair (paired rounds, for a shared machine whose speed drifts between runs more\n"
      "than the change to judge): each pair's runs were taken one after the other, alternating\n"
      "which went first; change = median over pairs of new/old frame median - 1, and p is a\n"
      "one-sided Wilcoxon signed-rank test of the log ratios over the pairs (exact up to 20\n"
      "pairs); at alpha 0.05, 5 pairs are the fewest that can be judged. Passes are not listed;\n"
      "work is compared between the first pair.\n"
      "Exit status: 0 no regression, 1 a case SLOWER (or, with --fail-on-work-change, a work\n"
      "change), 2 bad input (runs that share no case included).");
  cmd->callback([=] {
    runGuarded("compare-runs", [&] {
      CompareRunsOptions opt;
      std::string t = *threshold;
      if (!t.empty() && t.back() == '%') t.pop_back();
      std::size_t used = 0;
      try {
        opt.thresholdPct = std::stod(t, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (t.empty() || used != t.size() || !std::isfinite(opt.thresholdPct) || opt.thresholdPct < 0)
        throw InputError("--threshold " + *threshold + ": not a percentage >= 0");
      opt.alpha = *alpha;
      opt.correction = *correction == "none" ? Correction::None : Correction::Holm;
      opt.failOnWorkChange = *failOnWork;
      if (pairs->size() % 2 != 0)
        throw InputError("--pair needs two runs, OLD and NEW; got " +
                         std::to_string(pairs->size()) + " values");
      std::vector<std::pair<std::string, std::string>> more;
      for (std::size_t i = 0; i + 1 < pairs->size(); i += 2)
        more.emplace_back((*pairs)[i], (*pairs)[i + 1]);
      return runCompareRuns(*oldPath, *newPath, opt, *asJson, std::cout, more);
    });
  });
}

}  // namespace sb
