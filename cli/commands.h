// The subcommands of the CLI. registerCommands adds them all: list, render and compare
// (cli/commands.cpp), and those of the functions below, in the files they name. Each
// command's body runs under runGuarded.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "harness/checks.h"
#include "harness/settings.h"

namespace sb {

void registerCommands(CLI::App& app);
// `check` and `bless` (cli/check_command.cpp).
void registerCheckCommands(CLI::App& app);
// `probe` (cli/probe_command.cpp).
void registerProbeCommand(CLI::App& app);
// `bench-shadows` and `bench-oit` (cli/bench_command.cpp).
void registerBenchCommand(CLI::App& app);
// `sweep`, `merge` and `report` (cli/sweep_command.cpp).
void registerSweepCommands(CLI::App& app);
// `compare-runs` (cli/compare_runs_command.cpp).
void registerCompareRunsCommand(CLI::App& app);
// `history` (cli/history_command.cpp).
void registerHistoryCommand(CLI::App& app);
// `view` (cli/view_command.cpp).
void registerViewCommand(CLI::App& app);
// `figure` (cli/figure_command.cpp).
void registerFigureCommand(CLI::App& app);
// `bsdf-probe` (cli/bsdf_probe_command.cpp).
void registerBsdfProbeCommand(CLI::App& app);
int lastCommandStatus();
// --driver on a command without the render settings (check, sweep): main() has
// already acted on it (backends/driver_env.h); the option is for --help and parsing.
void addDriverOption(CLI::App& cmd);
// The line printed for an error CLI11 raised while parsing `args` (argv without
// the program): "strandbench: ..." with the closest command for one that is not
// a command, the flag given twice for one that takes one value; CLI11's own
// wording otherwise.
std::string parseErrorMessage(const CLI::App& app, const CLI::ParseError& error,
                              const std::vector<std::string>& args);
// Runs a command's body and records its exit status; bad input (InputError) and
// unavailable backends (DeviceError) print "strandbench <command>: <message>"
// to stderr and give status 2.
void runGuarded(const char* command, const std::function<int()>& body);

}  // namespace sb
