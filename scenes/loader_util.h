// Private helpers shared by the strand and mesh loaders (not part of the public API).
// Every read is bounds-checked: the loaders are fuzzed.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace sb::detail {

// Reads a whole file; throws InputError("cannot open '<path>': <reason>").
std::vector<uint8_t> readFileBytes(const std::string& path);

// "<name>: <what>" as an InputError.
[[noreturn]] void fail(const std::string& name, const std::string& what);

// The mesh's normals: `given` (per position) where it is not zero, else
// area-weighted from the triangles; unit length. `given` may be empty.
void setNormals(Mesh& m, const std::vector<glm::vec3>& given);

inline bool finite3(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Little-endian scalar reads at an offset the caller has already bounds-checked.
inline uint32_t rdU32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
inline uint16_t rdU16(const uint8_t* p) { return uint16_t(p[0] | p[1] << 8); }
inline float rdF32(const uint8_t* p) {
  uint32_t u = rdU32(p);
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

// Default per-point attributes for formats that do not store them.
inline constexpr float kDefaultThickness = 0.005f;
inline const glm::vec3 kDefaultHairColor{0.45f, 0.3f, 0.18f};

}  // namespace sb::detail
