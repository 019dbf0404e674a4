// The default reference (`--reference`, `--reference exact`): exact shadows and exact
// transparency at one sample per pixel, rendered with the run itself
// (harness/render_measures.cpp, renderReference); the others build on its shadow.
#pragma once

#include <cstdint>

#include "base/options.h"

namespace sb {

// The reference's transparency: exact, from sorted fragment lists.
extern const char* kReferenceOit;
// The reference for a technique: exact shadows at its light-map size, its lookup jittered as
// the technique's is (jitter, jitter_samples).
Spec referenceShadowSpec(const Spec& shadow);

// The light map of the reference's shadow (refShadow): its size and depth bias, read through
// the shadow technique's own descriptor (the shared declarations opt::mapSize and opt::bias).
struct ReferenceLightMap {
  uint32_t size = 0;
  double bias = 0;
};
ReferenceLightMap referenceLightMap(const Spec& refShadow);
// refShadow with a light map of `size` texels on a side.
Spec withLightMapSize(const Spec& refShadow, uint32_t size);

}  // namespace sb
