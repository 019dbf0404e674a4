// The machine, build and shard a run is made on (harness/run_context.h).
#include "harness/run_context.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "base/errors.h"

namespace sb {

namespace fs = std::filesystem;

namespace {

// First line of a command's output ("" when it fails).
std::string commandLine(const std::string& cmd) {
  std::string out;
  if (FILE* p = ::popen(cmd.c_str(), "r")) {
    char buf[512];
    if (std::fgets(buf, sizeof buf, p)) out = buf;
    ::pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

std::string fileValue(const std::string& path, const std::string& key, char sep) {
  std::ifstream f(path);
  std::string line;
  while (std::getline(f, line)) {
    if (line.rfind(key, 0) != 0) continue;
    auto pos = line.find(sep);
    if (pos == std::string::npos) continue;
    std::string v = line.substr(pos + 1);
    while (!v.empty() && (v.front() == ' ' || v.front() == '"')) v.erase(v.begin());
    while (!v.empty() && (v.back() == ' ' || v.back() == '"')) v.pop_back();
    return v;
  }
  return "";
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace

std::pair<int, int> parseShard(const std::string& text) {
  int i = 0, n = 0;
  char slash = 0;
  std::istringstream in(text);
  if (!(in >> i >> slash >> n) || slash != '/' || !in.eof() || n < 1 || i < 1 || i > n)
    throw InputError("--shard " + text + ": expected I/N with 1 <= I <= N, e.g. 2/4");
  return {i, n};
}

namespace {

// A scheduler variable as a whole number; InputError naming it otherwise.
int envNumber(const std::function<const char*(const char*)>& env, const char* name) {
  const char* v = env(name);
  if (!v) throw InputError(std::string("--shard auto: ") + name + " is not set");
  std::istringstream in(v);
  long n = 0;
  if (!(in >> n) || !in.eof() || n < 0 || n > 1000000)
    throw InputError(std::string("--shard auto: ") + name + "=" + v +
                     " is not a whole number in 0..1000000");
  return static_cast<int>(n);
}

}  // namespace

AutoShard shardFromEnvironment(const std::string& text,
                               const std::function<const char*(const char*)>& env) {
  // "auto" or "auto/N": N is the count for schedulers that give only an index.
  int given = 0;
  if (text != "auto") {
    std::istringstream in(text.substr(text.find('/') + 1));
    if (text.rfind("auto/", 0) != 0 || !(in >> given) || !in.eof() || given < 1)
      throw InputError("--shard " + text + ": expected I/N, auto or auto/N (N >= 1)");
  }
  AutoShard s;
  auto check = [&](const std::string& what) {
    if (s.count < 1 || s.index < 1 || s.index > s.count)
      throw InputError("--shard auto: " + what + " gives shard " + std::to_string(s.index) +
                       " of " + std::to_string(s.count) + ", outside 1.." +
                       std::to_string(s.count));
    if (given && given != s.count)
      throw InputError("--shard " + text + ": " + what + " says " + std::to_string(s.count) +
                       " shards");
    return s;
  };
  if (env("SLURM_ARRAY_TASK_ID")) {
    // An array --array=MIN-MAX[:STEP]: the tasks are MIN, MIN+STEP, ... (COUNT of them).
    const int id = envNumber(env, "SLURM_ARRAY_TASK_ID");
    const int min = env("SLURM_ARRAY_TASK_MIN") ? envNumber(env, "SLURM_ARRAY_TASK_MIN") : 0;
    const int step = env("SLURM_ARRAY_TASK_STEP") ? envNumber(env, "SLURM_ARRAY_TASK_STEP") : 1;
    s.count = env("SLURM_ARRAY_TASK_COUNT") ? envNumber(env, "SLURM_ARRAY_TASK_COUNT") : given;
    if (s.count == 0)
      throw InputError(
          "--shard auto: SLURM_ARRAY_TASK_ID is set but SLURM_ARRAY_TASK_COUNT is "
          "not; give the count as --shard auto/N");
    if (step < 1 || id < min || (id - min) % step != 0)
      throw InputError(
          "--shard auto: SLURM_ARRAY_TASK_ID=" + std::to_string(id) +
          " is not on the array's steps from SLURM_ARRAY_TASK_MIN=" + std::to_string(min));
    s.index = (id - min) / step + 1;
    s.source = "SLURM_ARRAY_TASK_ID";
    return check("SLURM_ARRAY_TASK_ID/SLURM_ARRAY_TASK_COUNT");
  }
  if (env("JOB_COMPLETION_INDEX")) {
    if (!given)
      throw InputError(
          "--shard auto: JOB_COMPLETION_INDEX (a Kubernetes indexed job) gives no "
          "count; give it as --shard auto/N with N the job's completions");
    s.index = envNumber(env, "JOB_COMPLETION_INDEX") + 1;
    s.count = given;
    s.source = "JOB_COMPLETION_INDEX";
    return check("JOB_COMPLETION_INDEX");
  }
  if (env("CI_NODE_INDEX")) {
    s.index = envNumber(env, "CI_NODE_INDEX");
    s.count = envNumber(env, "CI_NODE_TOTAL");
    s.source = "CI_NODE_INDEX";
    return check("CI_NODE_INDEX/CI_NODE_TOTAL");
  }
  if (env("GTEST_SHARD_INDEX")) {
    s.index = envNumber(env, "GTEST_SHARD_INDEX") + 1;
    s.count = envNumber(env, "GTEST_TOTAL_SHARDS");
    s.source = "GTEST_SHARD_INDEX";
    return check("GTEST_SHARD_INDEX/GTEST_TOTAL_SHARDS");
  }
  throw InputError(
      "--shard " + text +
      ": no scheduler's shard variable is set; expected one of SLURM_ARRAY_TASK_ID (with "
      "SLURM_ARRAY_TASK_COUNT, SLURM_ARRAY_TASK_MIN: a Slurm job array), JOB_COMPLETION_INDEX "
      "(a Kubernetes indexed job, with --shard auto/N), CI_NODE_INDEX and CI_NODE_TOTAL (GitLab "
      "parallel jobs), GTEST_SHARD_INDEX and GTEST_TOTAL_SHARDS; or give --shard I/N");
}

nlohmann::json loadAverage() {
  std::ifstream f("/proc/loadavg");
  double one = 0, five = 0, fifteen = 0;
  if (!(f >> one >> five >> fifteen)) return nullptr;
  return {{"1min", one}, {"5min", five}, {"15min", fifteen}};
}

std::string cpuGovernor() {
  // Every CPU's governor; one name when they agree ("performance"), else each distinct one.
  std::set<std::string> seen;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator("/sys/devices/system/cpu", ec)) {
    std::ifstream f(e.path() / "cpufreq" / "scaling_governor");
    std::string g;
    if (f >> g) seen.insert(g);
  }
  std::string out;
  for (const auto& g : seen) out += (out.empty() ? "" : ",") + g;
  return out;
}

std::string uncommittedCode() {
  // docs/ and README.md are what the runs write (pages, stored runs), not code that runs.
  return commandLine(std::string("git -C '") + SB_SOURCE_DIR +
                     "' status --porcelain --untracked-files=no -- . ':!docs' ':!README.md' "
                     "2>/dev/null");
}

nlohmann::json runContext() {
  nlohmann::json c;
  c["date"] = utcNow();
  const std::string git = std::string("git -C '") + SB_SOURCE_DIR + "' ";
  const std::string commit = commandLine(git + "rev-parse HEAD 2>/dev/null");
  c["commit"] = commit.empty() ? nlohmann::json(nullptr) : nlohmann::json(commit);
  c["commit_dirty"] = !commit.empty() && !uncommittedCode().empty();
  c["build_type"] = SB_BUILD_TYPE;
#if defined(__clang__)
  c["compiler"] = std::string("Clang ") + __clang_version__;
#elif defined(__GNUC__)
  c["compiler"] = "GNU " + std::to_string(__GNUC__) + "." + std::to_string(__GNUC_MINOR__) + "." +
                  std::to_string(__GNUC_PATCHLEVEL__);
#endif
  c["cpu"] = fileValue("/proc/cpuinfo", "model name", ':') + " (" +
             std::to_string(std::thread::hardware_concurrency()) + " threads)";
  c["os"] = fileValue("/etc/os-release", "PRETTY_NAME", '=');
  c["load_before"] = loadAverage();
  const std::string governor = cpuGovernor();
  c["cpu_governor"] = governor.empty() ? nlohmann::json(nullptr) : nlohmann::json(governor);
  return c;
}

}  // namespace sb
