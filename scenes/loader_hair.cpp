// Cem Yuksel's HAIR format: a 128-byte header followed by optional arrays
// (segments, points, thickness, transparency, colours), in that order.
#include <algorithm>
#include <limits>

#include "scenes/loader_util.h"
#include "scenes/scene.h"

namespace sb {

namespace {

constexpr std::size_t kHeaderSize = 128;
constexpr uint32_t kHasSegments = 1u << 0;
constexpr uint32_t kHasPoints = 1u << 1;
constexpr uint32_t kHasThickness = 1u << 2;
constexpr uint32_t kHasTransparency = 1u << 3;
constexpr uint32_t kHasColors = 1u << 4;

}  // namespace

Strands parseHair(const uint8_t* data, std::size_t size, const std::string& name) {
  using detail::fail;
  if (data == nullptr || size < kHeaderSize) {
    fail(name, "too short for a HAIR header (" + std::to_string(size) + " bytes, need 128)");
  }
  if (data[0] != 'H' || data[1] != 'A' || data[2] != 'I' || data[3] != 'R') {
    fail(name, "not a HAIR file (the first 4 bytes are not \"HAIR\")");
  }
  const uint64_t numStrands = detail::rdU32(data + 4);
  const uint64_t numPoints = detail::rdU32(data + 8);
  const uint32_t flags = detail::rdU32(data + 12);
  const uint64_t defSegments = detail::rdU32(data + 16);
  const float defThickness = detail::rdF32(data + 20);
  const float defTransparency = detail::rdF32(data + 24);
  const glm::vec3 defColor(detail::rdF32(data + 28), detail::rdF32(data + 32),
                           detail::rdF32(data + 36));

  if (numStrands == 0) fail(name, "header says zero strands");
  if (numPoints == 0) fail(name, "header says zero points");
  if (!(flags & kHasPoints)) {
    fail(name, "has no points array (flag bit 1 is clear): nothing to draw");
  }

  // Array sizes, in 64-bit arithmetic (counts are 32-bit, so no overflow).
  const uint64_t segBytes = (flags & kHasSegments) ? numStrands * 2 : 0;
  const uint64_t pointBytes = numPoints * 12;
  const uint64_t thickBytes = (flags & kHasThickness) ? numPoints * 4 : 0;
  const uint64_t transBytes = (flags & kHasTransparency) ? numPoints * 4 : 0;
  const uint64_t colorBytes = (flags & kHasColors) ? numPoints * 12 : 0;
  const uint64_t need = kHeaderSize + segBytes + pointBytes + thickBytes + transBytes + colorBytes;
  if (need > size) {
    fail(name, "truncated: header counts (" + std::to_string(numStrands) + " strands, " +
                   std::to_string(numPoints) + " points) need " + std::to_string(need) +
                   " bytes but the file has " + std::to_string(size));
  }

  Strands s;
  const uint8_t* p = data + kHeaderSize;

  // Strand sizes.
  if (flags & kHasSegments) {
    s.pointCount.resize(numStrands);
    for (uint64_t i = 0; i < numStrands; ++i)
      s.pointCount[i] = uint32_t(detail::rdU16(p + 2 * i)) + 1;
    p += segBytes;
  } else {
    if (defSegments >= std::numeric_limits<uint32_t>::max() ||
        numStrands * (defSegments + 1) != numPoints) {
      fail(name, "no segments array and " + std::to_string(numStrands) + " strands x (" +
                     std::to_string(defSegments) + " default segments + 1) != " +
                     std::to_string(numPoints) + " points in the header");
    }
    s.pointCount.assign(numStrands, uint32_t(defSegments + 1));
  }
  s.firstPoint.resize(numStrands);
  uint64_t total = 0;
  for (uint64_t i = 0; i < numStrands; ++i) {
    s.firstPoint[i] = uint32_t(std::min<uint64_t>(total, std::numeric_limits<uint32_t>::max()));
    total += s.pointCount[i];
  }
  if (total != numPoints) {
    fail(name, "segments array gives " + std::to_string(total) + " points but the header says " +
                   std::to_string(numPoints));
  }

  // Points.
  s.points.resize(numPoints);
  for (uint64_t i = 0; i < numPoints; ++i) {
    const uint8_t* q = p + 12 * i;
    s.points[i] = glm::vec3(detail::rdF32(q), detail::rdF32(q + 4), detail::rdF32(q + 8));
    if (!detail::finite3(s.points[i])) {
      fail(name, "point " + std::to_string(i) + " has a NaN or infinite coordinate");
    }
  }
  p += pointBytes;

  auto readScalars = [&](std::vector<float>& out, bool present, float def, const char* what) {
    if (present) {
      out.resize(numPoints);
      for (uint64_t i = 0; i < numPoints; ++i) {
        out[i] = detail::rdF32(p + 4 * i);
        if (!std::isfinite(out[i])) {
          fail(name, std::string(what) + " of point " + std::to_string(i) + " is NaN or infinite");
        }
      }
      p += numPoints * 4;
    } else {
      if (!std::isfinite(def)) fail(name, std::string("default ") + what + " is NaN or infinite");
      out.assign(numPoints, def);
    }
  };
  readScalars(s.thickness, flags & kHasThickness, defThickness, "thickness");
  readScalars(s.transparency, flags & kHasTransparency, defTransparency, "transparency");

  if (flags & kHasColors) {
    s.colors.resize(numPoints);
    for (uint64_t i = 0; i < numPoints; ++i) {
      const uint8_t* q = p + 12 * i;
      s.colors[i] = glm::vec3(detail::rdF32(q), detail::rdF32(q + 4), detail::rdF32(q + 8));
      if (!detail::finite3(s.colors[i])) {
        fail(name, "colour of point " + std::to_string(i) + " is NaN or infinite");
      }
    }
  } else {
    if (!detail::finite3(defColor)) fail(name, "default colour is NaN or infinite");
    s.colors.assign(numPoints, defColor);
  }
  return s;
}

}  // namespace sb
