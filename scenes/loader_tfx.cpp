// AMD TressFX .tfx: float version, uint32 numStrands, uint32 numVerticesPerStrand,
// uint32 offsetVertexPosition, ... Version 3 files (bear.tfx) have a 296-byte header
// with float3 positions right after it (offsetVertexPosition 0); version 4 files
// (Ratboy_mohawk.tfx) have a 160-byte header and float4 positions at offsetVertexPosition.
#include <cmath>
#include <limits>

#include "scenes/loader_util.h"
#include "scenes/scene.h"

namespace sb {

Strands parseTfx(const uint8_t* data, std::size_t size, const std::string& name) {
  using detail::fail;
  if (data == nullptr || size < 16) {
    fail(name, "too short for a TressFX header (" + std::to_string(size) + " bytes)");
  }
  const float version = detail::rdF32(data);
  uint64_t headerSize = 0, stride = 0;
  if (version == 3.0f) {
    headerSize = 296;
    stride = 12;
  } else if (version == 4.0f) {
    headerSize = 160;
    stride = 16;
  } else {
    fail(name,
         "unsupported TressFX version " +
             (std::isfinite(version) ? std::to_string(version) : std::string("(not a number)")) +
             " (expected 3.0 or 4.0)");
  }
  if (size < headerSize) {
    fail(name, "truncated: the version " + std::to_string(int(version)) + " header needs " +
                   std::to_string(headerSize) + " bytes but the file has " + std::to_string(size));
  }
  const uint64_t numStrands = detail::rdU32(data + 4);
  const uint64_t perStrand = detail::rdU32(data + 8);
  uint64_t offset = detail::rdU32(data + 12);
  if (numStrands == 0) fail(name, "header says zero strands");
  if (perStrand == 0) fail(name, "header says zero vertices per strand");
  if (offset == 0) offset = headerSize;
  if (offset < headerSize) {
    fail(name, "vertex position offset " + std::to_string(offset) + " lies inside the " +
                   std::to_string(headerSize) + "-byte header");
  }
  const uint64_t numPoints = numStrands * perStrand;  // < 2^64: both are 32-bit
  if (numPoints > std::numeric_limits<uint32_t>::max() || offset > size ||
      numPoints > (size - offset) / stride) {
    fail(name, "truncated: " + std::to_string(numStrands) + " strands x " +
                   std::to_string(perStrand) + " vertices need " +
                   std::to_string(numPoints * stride) + " bytes of positions at offset " +
                   std::to_string(offset) + " but the file has " + std::to_string(size));
  }

  Strands s;
  s.firstPoint.resize(numStrands);
  s.pointCount.assign(numStrands, uint32_t(perStrand));
  for (uint64_t i = 0; i < numStrands; ++i) s.firstPoint[i] = uint32_t(i * perStrand);
  s.points.resize(numPoints);
  const uint8_t* p = data + offset;
  for (uint64_t i = 0; i < numPoints; ++i) {
    const uint8_t* q = p + stride * i;
    s.points[i] = glm::vec3(detail::rdF32(q), detail::rdF32(q + 4), detail::rdF32(q + 8));
    if (!detail::finite3(s.points[i])) {
      fail(name, "vertex " + std::to_string(i) + " has a NaN or infinite coordinate");
    }
  }
  s.colors.assign(numPoints, detail::kDefaultHairColor);
  s.thickness.assign(numPoints, detail::kDefaultThickness);
  s.transparency.assign(numPoints, 0.0f);
  return s;
}

}  // namespace sb
