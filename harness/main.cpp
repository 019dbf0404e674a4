// strandbench: the command line. Exit status 0 on success, 1 for a failed
// check, 2 for bad input or an unavailable backend.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>

#include "backends/device.h"
#include "harness/commands.h"
#include "harness/version.h"

int main(int argc, char** argv) {
  CLI::App app{"strandbench: benchmark and visual-regression harness for strand rendering"};
  app.require_subcommand(1);
  app.set_version_flag(
      "--version", [] { return sb::versionText(); },
      "Print version, commit, build type and the devices and drivers found");
  sb::registerCommands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "strandbench: " << e.what() << "\n";
    return 2;
  }
  return sb::lastCommandStatus();
}
