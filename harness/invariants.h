// Invariants every run must keep, however stiff the case (the extreme suite):
// finite outputs and maps, visibility in [0, 1] and non-increasing along a
// light ray, colours within what the inputs can produce. Each failure names
// the pass or resource it was found in.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "backends/device.h"
#include "imaging/image.h"

namespace sb {

struct InvariantFailure {
  std::string pass;  // the pass or resource that produced the value
  std::string what;
};

// Colour: finite and in [0, maxRadiance] (plus a small tolerance).
void checkColor(const Image& color, float maxRadiance, const std::string& pass,
                std::vector<InvariantFailure>& out);
// Visibility image (R32F, -1 where no surface): finite, -1 or in [0, 1].
void checkVisibility(const std::vector<uint8_t>& r32f, const std::string& pass,
                     std::vector<InvariantFailure>& out);
// Visibility along a light ray, from the light: finite, in [0, 1], and
// non-increasing unless `monotone` is false (a technique that does not
// promise it: ShadowTechnique::monotone()).
void checkRay(const std::vector<float>& curve, const std::string& pass,
              std::vector<InvariantFailure>& out, bool monotone = true);
// A read-back map: no NaN or Inf in any float channel (integer formats hold none).
void checkMap(const std::vector<uint8_t>& bytes, Format format, const std::string& name,
              std::vector<InvariantFailure>& out);

}  // namespace sb
