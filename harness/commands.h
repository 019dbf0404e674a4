// The subcommands of the CLI (list, render, compare, check, bless).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace sb {
void registerCommands(CLI::App& app);
// `check` and `bless` (harness/check_command.cpp).
void registerCheckCommands(CLI::App& app);
// `probe` (harness/probe_command.cpp).
void registerProbeCommand(CLI::App& app);
// `bench-shadows` (harness/bench_command.cpp).
void registerBenchCommand(CLI::App& app);
// `sweep`, `merge` and `report` (harness/sweep_command.cpp).
void registerSweepCommands(CLI::App& app);
// `compare-runs` (harness/compare_runs.cpp).
void registerCompareRunsCommand(CLI::App& app);
int lastCommandStatus();
// Runs a command's body and records its exit status; bad input (InputError) and
// unavailable backends (DeviceError) print "strandbench <command>: <message>"
// to stderr and give status 2.
void runGuarded(const char* command, const std::function<int()>& body);
}  // namespace sb
