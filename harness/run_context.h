// Where and how a run is made: the machine and build (for every results file and
// generated table), and the shard a scheduler gave this process.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

namespace sb {

// "I/N" -> (I, N) with 1 <= I <= N.
std::pair<int, int> parseShard(const std::string& text);

// The shard a scheduler gave this process (`--shard auto`, or `auto/N` where the scheduler
// gives only an index): Slurm job arrays (SLURM_ARRAY_TASK_ID, _COUNT, _MIN, _STEP),
// Kubernetes indexed jobs (JOB_COMPLETION_INDEX, 0-based, with N given), GitLab parallel jobs
// (CI_NODE_INDEX, CI_NODE_TOTAL, 1-based) and GoogleTest sharding (GTEST_SHARD_INDEX,
// GTEST_TOTAL_SHARDS, 0-based), in that order. `env` reads a variable (nullptr: unset).
// Returns (I, N, the variable used); throws InputError naming the variables when none is set
// or one is malformed.
struct AutoShard {
  int index = 1, count = 1;
  std::string source;
};
AutoShard shardFromEnvironment(const std::string& text,
                               const std::function<const char*(const char*)>& env);

// The machine and build a run was made on (date, commit, build type, compiler, CPU, OS, the
// load average when it starts, the CPU frequency governor where /sys shows it).
nlohmann::json runContext();
// The first tracked file of the source tree with uncommitted changes (git status --porcelain),
// docs/ and README.md aside (the runs write them); "" on a clean tree or without git.
std::string uncommittedCode();
// /proc/loadavg as {"1min", "5min", "15min"}; null where it cannot be read.
nlohmann::json loadAverage();
// The CPUs' cpufreq scaling governors ("performance", or "a,b" when they differ); "" where
// cpufreq is not visible (virtual machines, containers).
std::string cpuGovernor();

}  // namespace sb
