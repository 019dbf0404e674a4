// hostMemoryBudget (backends/device.h): the CPU drivers' device memory is the
// host's, so their budget is what this process can still take from it.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "backends/device.h"

namespace sb {

namespace {
// A "Key:   123 kB" line of a /proc file, in bytes (0 when absent).
std::size_t procKilobytes(const char* file, const std::string& key) {
  std::ifstream f(file);
  std::string line;
  while (std::getline(f, line))
    if (line.rfind(key + ":", 0) == 0) return std::stoull(line.substr(key.size() + 1)) * 1024;
  return 0;
}
}  // namespace

MemoryBudget hostMemoryBudget() {
  MemoryBudget b;
  b.bytes = procKilobytes("/proc/meminfo", "MemAvailable");
  if (b.bytes) b.source = "host MemAvailable";
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    // Address space already mapped counts against the limit (libraries,
    // thread stacks, the drivers' heaps), not only the memory in use.
    const std::size_t mapped = procKilobytes("/proc/self/status", "VmSize");
    const std::size_t left = limit.rlim_cur > mapped ? limit.rlim_cur - mapped : 0;
    if (!b.bytes || left < b.bytes) {
      b.bytes = left;
      b.source = "address-space limit (RLIMIT_AS " + std::to_string(limit.rlim_cur) + " bytes, " +
                 std::to_string(mapped) + " mapped)";
    }
  }
  return b;
}

}  // namespace sb
