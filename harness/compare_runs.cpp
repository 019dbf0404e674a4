// `strandbench compare-runs` (placeholder until implemented).
#include "harness/commands.h"

namespace sb {
void registerCompareRunsCommand(CLI::App&) {}
}  // namespace sb
