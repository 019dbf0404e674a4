// `strandbench sweep`, `merge` and `report` (placeholder until implemented).
#include "harness/commands.h"

namespace sb {
void registerSweepCommands(CLI::App&) {}
}  // namespace sb
