// strandbench: the command line. Exit status 0 on success, 1 for a failed
// check (or a sweep with failed cases), 2 for bad input, an unavailable backend
// or memory that is not there, 130 / 143 when stopped by SIGINT / SIGTERM.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "backends/device.h"
#include "backends/driver_env.h"
#include "cli/commands.h"
#include "harness/stop.h"
#include "harness/version.h"

namespace {
// The CPU drivers (llvmpipe, lavapipe) allocate and free large buffers on
// every draw. With glibc's defaults, whether those frees go back to the
// system (and the next draw page-faults them in again) depends on the heap's
// layout, which any unrelated change in this program moves: the same peeling
// frame took 208 or 285 ms in two builds issuing identical GL calls and
// shaders. Fixed thresholds keep the memory in the process, so timings
// measure rendering, not the allocator.
void pinAllocator() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);   // glibc's largest allowed value
  mallopt(M_TRIM_THRESHOLD, 512 << 20);  // keep up to 512 MiB of freed heap
#endif
}
}  // namespace

int main(int argc, char** argv) {
  // Before anything loads a GL or Vulkan library: --driver re-executes the process with
  // that driver's loader environment.
  sb::selectDriverFromArgs(argc, argv);
  // Hidden: one driver's devices for `--version`, which runs this per driver.
  if (argc == 2 && std::string(argv[1]) == "--version-probe") {
    std::cout << sb::versionProbeText();
    return 0;
  }
  pinAllocator();
  sb::installStopHandlers();
  CLI::App app{"strandbench: benchmark and visual-regression harness for strand rendering"};
  app.require_subcommand(1);
  app.set_version_flag(
      "--version", [] { return sb::versionText(); },
      "Print version, commit, build type and the devices and drivers found");
  sb::registerCommands(app);
  // Bare `strandbench` does nothing: say what it does instead (CLI11 would only
  // say that a subcommand is required).
  if (argc == 1) {
    std::cerr << "strandbench: give a command\n\n" << app.help();
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << sb::parseErrorMessage(app, e, std::vector<std::string>(argv + 1, argv + argc))
              << "\n";
    return 2;
  }
  return sb::lastCommandStatus();
}
