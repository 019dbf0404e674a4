// `strandbench sweep`, `merge`, `report` and `driver-ab` (harness/sweep.h and
// harness/driver_ab.h do the work).
#include <unistd.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "backends/driver_env.h"
#include "cli/commands.h"
#include "harness/driver_ab.h"
#include "harness/sweep.h"

namespace sb {

void registerSweepCommands(CLI::App& app) {
  {
    auto* cmd = app.add_subcommand(
        "sweep", "run a suite (suites/*.json) into a folder, then write its reports");
    auto o = std::make_shared<SweepOptions>();
    auto shard = std::make_shared<std::string>();
    cmd->add_option("suite", o->suitePath, "suite file, e.g. suites/quick.json")->required();
    cmd->add_option("--out", o->out, "output folder")->required();
    cmd->add_option("--filter", o->filter, "run only cases whose id matches this regex");
    cmd->add_flag("--resume", o->resume, "continue a stopped sweep: skip the cases already done");
    cmd->add_option("--shard", *shard,
                    "run shard I of N (I in 1..N), or `auto` (`auto/N`): the shard a scheduler "
                    "gives (Slurm array, Kubernetes indexed job, GitLab parallel, GTest "
                    "sharding); join them with `merge`");
    cmd->add_flag(
        "--fail-fast", o->failFast,
        "stop at the first failed case (default: record it and go on; exit 1 at the end)");
    cmd->add_flag("--require-drivers", o->requireParts,
                  "fail (exit 1) when a case could not run for a part this machine lacks (a "
                  "driver not installed, ray queries); default: list those cases and go on "
                  "(exit 0 for them). CI=true sets it");
    auto runs = std::make_shared<CliRunOptions>(
        *cmd,
        "interleaved, each rendering every case of a group once; default: the group's "
        "largest `repeat`");
    addDriverOption(*cmd);
    // Internal: a child sweep of the cases on its --driver (harness/sweep.h).
    cmd->add_flag("--driver-cases", o->driverCasesOnly)->group("");
    cmd->add_flag("--interleave,!--no-interleave", o->interleave,
                  "measure a group's cases in interleaved rounds (default), or each case's "
                  "`repeat` frames back to back in one run");
    cmd->callback([o, shard, runs] {
      runGuarded("sweep", [&] {
        o->rounds = runs->read();
        if (shard->rfind("auto", 0) == 0) {
          const AutoShard a =
              shardFromEnvironment(*shard, [](const char* name) { return std::getenv(name); });
          o->shardIndex = a.index;
          o->shardCount = a.count;
          o->shardSource = a.source;
        } else if (!shard->empty()) {
          std::tie(o->shardIndex, o->shardCount) = parseShard(*shard);
        }
        o->progressBar = ::isatty(STDOUT_FILENO) != 0;
        // In CI a missing part fails, as a test that cannot find its backend does.
        const char* ci = std::getenv("CI");
        if (ci && std::string(ci) == "true") o->requireParts = true;
        return runSweep(*o);
      });
    });
  }
  {
    auto* cmd = app.add_subcommand("report",
                                   "write results.json, results.csv, passes.csv, cost_model.json, "
                                   "report.md and report.html of a sweep folder");
    auto dir = std::make_shared<std::string>();
    cmd->add_option("dir", *dir, "sweep folder")->required();
    cmd->callback([dir] {
      runGuarded("report", [&] {
        const int n = writeSweepReport(*dir);
        std::cout
            << "wrote " << *dir << "/results.json (" << n
            << " results), results.csv, passes.csv, cost_model.json, report.md, report.html\n";
        return 0;
      });
    });
  }
  {
    auto* cmd = app.add_subcommand(
        "driver-ab",
        "sweep a suite on two drivers and write a triage page (OUT/ab.html): images, "
        "difference heatmap and FLIP map, times and work counters side by side");
    auto o = std::make_shared<DriverAbOptions>();
    cmd->add_option("suite", o->suitePath, "suite file, e.g. suites/quick.json")->required();
    cmd->add_option("--out", o->out, "output folder (OUT/a, OUT/b: the two sweeps)")->required();
    cmd->add_option("--a", o->a, std::string("driver A; ") + kDriverHelp)->capture_default_str();
    cmd->add_option("--b", o->b, "driver B (e.g. mesa-25.0)")->required();
    cmd->add_option("--filter", o->filter, "run only cases whose id matches this regex");
    cmd->add_flag("--resume", o->resume, "continue both sweeps of OUT");
    cmd->callback([o] { runGuarded("driver-ab", [&] { return runDriverAb(*o); }); });
  }
  {
    auto* page = app.add_subcommand("driver-ab-page", "rewrite OUT/ab.html of a driver A/B folder");
    auto dir = std::make_shared<std::string>();
    page->add_option("dir", *dir, "driver A/B folder")->required();
    page->callback([dir] {
      runGuarded("driver-ab-page", [&] {
        std::cout << "wrote " << *dir << "/ab.html (" << writeDriverAbPage(*dir)
                  << " cases paired)\n";
        return 0;
      });
    });
  }
  {
    auto* cmd =
        app.add_subcommand("merge", "join the folders of a sharded sweep into a new folder");
    auto out = std::make_shared<std::string>();
    auto inputs = std::make_shared<std::vector<std::string>>();
    auto allowMissing = std::make_shared<bool>(false);
    cmd->add_option("--out", *out, "new folder for the joined sweep")->required();
    cmd->add_option("dirs", *inputs, "shard folders")->required();
    cmd->add_flag("--allow-missing", *allowMissing,
                  "merge what is there when shards or cases are missing (default: name them, "
                  "write nothing, exit 1)");
    cmd->callback([out, inputs, allowMissing] {
      runGuarded("merge", [&] {
        const MergeOutcome m = mergeSweeps(*out, *inputs, *allowMissing);
        if (!m.missingCases.empty()) {
          std::ostream& s = m.written ? std::cout : std::cerr;
          s << (m.written ? "merge: warning: " : "merge: ");
          if (!m.missingShards.empty()) {
            s << "missing shard" << (m.missingShards.size() > 1 ? "s" : "");
            for (std::size_t i = 0; i < m.missingShards.size(); ++i)
              s << (i ? ", " : " ") << m.missingShards[i] << "/" << m.shardCount;
            s << "; ";
          }
          s << m.missingCases.size() << " case" << (m.missingCases.size() > 1 ? "s" : "")
            << " of the suite in no folder:";
          for (std::size_t i = 0; i < m.missingCases.size() && i < 10; ++i)
            s << (i ? ", " : " ") << m.missingCases[i];
          if (m.missingCases.size() > 10) s << ", ...";
          s << "\n";
          if (!m.written) {
            s << "merge: nothing written; add --allow-missing to merge what is there\n";
            return 1;
          }
        }
        std::cout << "merged " << inputs->size() << " folders into " << *out << " (" << m.results
                  << " results)\n";
        return 0;
      });
    });
  }
}

}  // namespace sb
