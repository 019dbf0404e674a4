// Shared by the loader fuzz targets. A loader given arbitrary bytes must either return
// well-formed data or throw sb::InputError naming the input; anything else (another
// exception, a crash, a sanitizer report, a hang, a huge allocation, inconsistent output)
// is a bug and aborts, so libFuzzer saves the input as a crash artifact.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "scenes/scene.h"

namespace sbfuzz {

// The name the loaders put in their messages.
inline const std::string kName = "fuzz-input";

[[noreturn]] inline void bug(const std::string& what) {
  std::fprintf(stderr, "fuzz: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

inline bool finite3(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The invariants the renderer relies on (as tests/test_util.h's expectWellFormed).
inline void checkStrands(const sb::Strands& s) {
  if (s.firstPoint.size() != s.pointCount.size()) bug("firstPoint and pointCount sizes differ");
  if (s.strandCount() == 0) bug("a successful load has no strands");
  const std::size_t n = s.points.size();
  if (s.colors.size() != n || s.thickness.size() != n || s.transparency.size() != n) {
    bug("per-point arrays differ in size");
  }
  uint64_t next = 0;
  for (std::size_t i = 0; i < s.strandCount(); ++i) {
    if (s.firstPoint[i] != next) bug("strand " + std::to_string(i) + " does not follow the last");
    if (s.pointCount[i] == 0) bug("strand " + std::to_string(i) + " has no points");
    next += s.pointCount[i];
  }
  if (next != n) bug("point counts do not add up to the points");
  for (std::size_t i = 0; i < n; ++i) {
    if (!finite3(s.points[i]) || !finite3(s.colors[i]) || !std::isfinite(s.thickness[i]) ||
        !std::isfinite(s.transparency[i])) {
      bug("point " + std::to_string(i) + " has a NaN or infinite attribute");
    }
  }
}

inline void checkMesh(const sb::Mesh& m) {
  if (m.positions.empty() || m.indices.empty()) bug("a successful load has no triangles");
  if (m.indices.size() % 3 != 0) bug("index count is not a multiple of 3");
  if (m.normals.size() != m.positions.size()) bug("normals and positions differ in size");
  for (uint32_t i : m.indices) {
    if (i >= m.positions.size()) bug("index " + std::to_string(i) + " out of range");
  }
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    if (!finite3(m.positions[i]) || !finite3(m.normals[i])) {
      bug("vertex " + std::to_string(i) + " has a NaN or infinite position or normal");
    }
  }
}

// Runs load() and checks its result; InputError is the expected outcome for most inputs.
template <class Load, class Check>
void run(Load&& load, Check&& check) {
  try {
    check(load());
  } catch (const sb::InputError& e) {
    if (std::string(e.what()).find(kName) == std::string::npos) {
      bug(std::string("InputError does not name the input: ") + e.what());
    }
  } catch (const std::exception& e) {
    bug(std::string("unexpected exception (not InputError): ") + e.what());
  }
}

}  // namespace sbfuzz
