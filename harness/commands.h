// The subcommands of the CLI (list, render, compare).
#pragma once

#include <CLI/CLI.hpp>

namespace sb {
void registerCommands(CLI::App& app);
int lastCommandStatus();
}  // namespace sb
