// The subcommands of the CLI. registerCommands adds them all: list, render and compare
// (harness/commands.cpp), and those of the functions below, in the files they name. Each
// command's body runs under runGuarded.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "harness/settings.h"

namespace sb {

void registerCommands(CLI::App& app);
// `check` and `bless` (harness/check_command.cpp).
void registerCheckCommands(CLI::App& app);
// `probe` (harness/probe_command.cpp).
void registerProbeCommand(CLI::App& app);
// `bench-shadows` and `bench-oit` (harness/bench_command.cpp).
void registerBenchCommand(CLI::App& app);
// `sweep`, `merge` and `report` (harness/sweep_command.cpp).
void registerSweepCommands(CLI::App& app);
// `compare-runs` (harness/compare_runs_command.cpp).
void registerCompareRunsCommand(CLI::App& app);
// `history` (harness/history_command.cpp).
void registerHistoryCommand(CLI::App& app);
// `view` (harness/view_command.cpp).
void registerViewCommand(CLI::App& app);
// `figure` (harness/figure_command.cpp).
void registerFigureCommand(CLI::App& app);
int lastCommandStatus();
// The line printed for an error CLI11 raised while parsing `args` (argv without
// the program): "strandbench: ..." with the closest command for one that is not
// a command, the flag given twice for one that takes one value; CLI11's own
// wording otherwise.
std::string parseErrorMessage(const CLI::App& app, const CLI::ParseError& error,
                              const std::vector<std::string>& args);
// `s` as one shell word: as it is when it holds only safe characters, else in
// single quotes (a command line printed for the user to run).
std::string shellQuoted(const std::string& s);
// Runs a command's body and records its exit status; bad input (InputError) and
// unavailable backends (DeviceError) print "strandbench <command>: <message>"
// to stderr and give status 2.
void runGuarded(const char* command, const std::function<int()>& body);

// Checks made before any work, so that bad input stops a command before it
// prints or writes anything; each throws InputError naming `option` and the path.
// An output file: its extension is one of `extensions` (".png"), its folder
// exists and is writable, and it is not a folder itself.
void checkOutputPath(const std::string& option, const std::string& path,
                     const std::vector<std::string>& extensions);
// An output folder made when first needed: the folder, or its nearest existing
// parent, is a writable folder (nothing is created).
void checkOutputFolder(const std::string& option, const std::string& path);
// Everything a render request names, without rendering: every setting's range
// (checkRequest), the scene (built, and kept in `cache` when given), the
// techniques and the view; with `device`, the backend's device is created once.
// Messages name the setting as `spelling` spells it ("--shadow x: ...").
void checkRenderRequest(const RenderRequest& req, bool device, RenderCache* cache = nullptr,
                        Spelling spelling = Spelling::Cli);
}  // namespace sb
