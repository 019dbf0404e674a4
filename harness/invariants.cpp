#include "harness/invariants.h"

#include <cmath>
#include <cstring>
#include <sstream>

namespace sb {

namespace {

constexpr float kTolerance = 1e-4f;  // float rounding in blending and interpolation

std::vector<float> floats(const std::vector<uint8_t>& bytes) {
  std::vector<float> v(bytes.size() / sizeof(float));
  std::memcpy(v.data(), bytes.data(), v.size() * sizeof(float));
  return v;
}

std::string at(std::size_t i, float v) {
  std::ostringstream s;
  s << " (first at index " << i << ": " << v << ")";
  return s.str();
}

}  // namespace

void checkColor(const Image& color, float maxRadiance, const std::string& pass,
                std::vector<InvariantFailure>& out) {
  std::size_t bad = 0, over = 0, firstBad = 0, firstOver = 0;
  for (std::size_t i = 0; i < color.pixels.size(); ++i) {
    const float v = color.pixels[i];
    if (!std::isfinite(v)) {
      if (!bad++) firstBad = i;
    } else if (v < -kTolerance || v > maxRadiance + kTolerance) {
      if (!over++) firstOver = i;
    }
  }
  if (bad)
    out.push_back({pass, "colour has " + std::to_string(bad) + " NaN or Inf values" +
                             at(firstBad, color.pixels[firstBad])});
  if (over)
    out.push_back({pass, "colour has " + std::to_string(over) + " values outside [0, " +
                             std::to_string(maxRadiance) + "], the most its inputs can give" +
                             at(firstOver, color.pixels[firstOver])});
}

void checkVisibility(const std::vector<uint8_t>& r32f, const std::string& pass,
                     std::vector<InvariantFailure>& out) {
  const std::vector<float> v = floats(r32f);
  std::size_t bad = 0, first = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const bool ok = v[i] == -1.0f || (v[i] >= -kTolerance && v[i] <= 1.0f + kTolerance);
    if (!ok && !bad++) first = i;
  }
  if (bad)
    out.push_back({pass, "visibility has " + std::to_string(bad) +
                             " values that are NaN, Inf or outside [0, 1]" + at(first, v[first])});
}

void checkRay(const std::vector<float>& curve, const std::string& pass,
              std::vector<InvariantFailure>& out, bool monotone) {
  for (std::size_t i = 0; i < curve.size(); ++i) {
    if (!(curve[i] >= -kTolerance && curve[i] <= 1.0f + kTolerance)) {
      out.push_back(
          {pass, "visibility along the light ray is NaN, Inf or outside [0, 1]" + at(i, curve[i])});
      return;
    }
    if (monotone && i > 0 && curve[i] > curve[i - 1] + kTolerance) {
      out.push_back({pass, "visibility along the light ray increases away from the light" +
                               at(i, curve[i]) + ", after " + std::to_string(curve[i - 1])});
      return;
    }
  }
}

void checkMap(const std::vector<uint8_t>& bytes, Format format, const std::string& name,
              std::vector<InvariantFailure>& out) {
  std::size_t bad = 0;
  if (format == Format::RGBA16F) {
    // Half floats: exponent bits all set is Inf or NaN.
    for (std::size_t i = 0; i + 1 < bytes.size(); i += 2) {
      uint16_t h = 0;
      std::memcpy(&h, &bytes[i], 2);
      bad += (h & 0x7c00u) == 0x7c00u;
    }
  } else if (format == Format::RGBA32F || format == Format::R32F || format == Format::RG32F ||
             format == Format::Depth32F) {
    for (float v : floats(bytes)) bad += !std::isfinite(v);
  }
  if (bad) out.push_back({name, "map has " + std::to_string(bad) + " NaN or Inf values"});
}

}  // namespace sb
