// `strandbench check` and `strandbench bless` (the logic is in harness/baselines.cpp).
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "harness/baselines.h"

namespace sb {

void registerCheckCommands(CLI::App& app) {
  {
    auto* cmd = app.add_subcommand(
        "check", "render the baseline cases and compare them with baselines/ (exit 1 on failure)");
    auto filter = std::make_shared<std::string>();
    auto baselines = std::make_shared<std::string>(defaultBaselinesDir().string());
    auto out = std::make_shared<std::string>("out/check");
    auto expectations = std::make_shared<std::string>();
    auto retries = std::make_shared<int>(2);
    cmd->add_option("--filter", *filter, "only the cases whose name matches this regex");
    cmd->add_option("--baselines", *baselines, "baselines folder (holds manifest.json)")
        ->capture_default_str();
    cmd->add_option("--out", *out, "where failures are written (actual, expected, diff, JSON)")
        ->capture_default_str();
    cmd->add_option("--expectations", *expectations,
                    "the driver's expected failures, flakes and skips (default: "
                    "BASELINES/expectations/DRIVER.json where it exists; none: none)");
    cmd->add_option("--retries", *retries,
                    "re-runs of a case with an unexpected failure: one that passes on a re-run "
                    "is a flake")
        ->capture_default_str();
    addDriverOption(*cmd);
    cmd->callback([=] {
      runGuarded("check", [&] {
        checkOutputFolder("--out", *out);  // written only on failure, but checked up front
        return runCheck({*baselines, *out, *filter, *expectations, *retries}, std::cout);
      });
    });
  }
  {
    auto* cmd = app.add_subcommand(
        "bless", "re-render the baseline images (staged, then swapped in atomically)");
    auto filter = std::make_shared<std::string>();
    auto baselines = std::make_shared<std::string>(defaultBaselinesDir().string());
    cmd->add_option("--filter", *filter, "only the cases whose name matches this regex");
    cmd->add_option("--baselines", *baselines, "baselines folder (holds manifest.json)")
        ->capture_default_str();
    cmd->callback(
        [=] { runGuarded("bless", [&] { return runBless(*baselines, *filter, std::cout); }); });
  }
}

}  // namespace sb
