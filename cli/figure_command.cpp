// `strandbench figure NAME`: parses the options; harness/figure.h runs the figure.
#include <unistd.h>

#include <iostream>
#include <memory>

#include "base/errors.h"
#include "cli/commands.h"
#include "harness/backend_names.h"
#include "harness/figure.h"
#include "harness/run_options.h"
#include "harness/setting_values.h"
#include "reports/json_file.h"

namespace sb {

using ojson = nlohmann::ordered_json;

void registerFigureCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "figure",
      "reproduce a paper's figure or table (suites/figures/NAME.json): its grid of "
      "images with error heatmaps (figure.png) and our numbers beside the paper's "
      "(figure.md)");
  auto o = std::make_shared<FigureOptions>();
  auto list = std::make_shared<bool>(false);
  cmd->add_option("name", o->name, "figure name (strandbench figure --list) or a figure file");
  cmd->add_flag("--list", *list, "list the figures");
  cmd->add_flag("--small", o->small,
                "the figure's small variant (smaller scene, size, repeats; under a minute)");
  std::vector<std::string> backends = backendNames();
  backends.push_back(kBothBackends);
  cmd->add_option("--backend", o->backend,
                  setting_values::joinOr(backends) +
                      " (both: every case on each API in one interleaved run, a row per API)")
      ->capture_default_str();
  auto runs = std::make_shared<CliRunOptions>(
      *cmd,
      "timed rounds per case; default: the figure's repeat: the frame samples the 95% "
      "intervals and the claims' verdicts are made of");
  cmd->add_option("--out", o->out, "output folder (default figures/NAME[-small]-BACKEND)");
  cmd->add_option("--docs", o->docs,
                  "also write DIR/NAME.md and DIR/NAME.png, the page the docs include "
                  "(docs/figures; its first line names the command, commit and digest)");
  cmd->add_option("--cases", o->cases,
                  "the shared case store, one folder for a whole refresh (default "
                  "$SB_FIGURE_CASES): a case another figure measured there on this build is "
                  "taken, not measured again, and this figure's cases are kept there")
      ->envname("SB_FIGURE_CASES");
  cmd->callback([o, list, runs] {
    runGuarded("figure", [&] {
      o->rounds = runs->read();
      if (*list) {
        for (const std::string& n : figureNames()) {
          std::string title;
          try {
            title = readJsonFile<ojson>(figuresDir() / (n + ".json"))["figure"].value("title", "");
          } catch (const InputError& e) {
            title = std::string("(unreadable: ") + e.what() + ")";
          }
          std::cout << n << "  " << title << "\n";
        }
        return 0;
      }
      if (o->name.empty()) {
        std::string names;
        for (const std::string& n : figureNames()) names += (names.empty() ? "" : ", ") + n;
        throw InputError("figure: name a figure; the figures: " + names);
      }
      o->progressBar = ::isatty(STDOUT_FILENO) != 0;
      return runFigure(*o);
    });
  });
}

}  // namespace sb
