// The generation rule of a groom (scenes/groom.h): how a rendered strand is made
// from the guide strands, written once for C++ (scenes/groom.cpp, the CPU path and
// every reference) and GLSL (render/generation/generate.comp, the GPU's
// compute pass), so both make the same strands bit for bit. Hence only +, -, *
// and integer hashing here: no division, sqrt or trigonometry (drivers round
// those differently), and every float result SB_PRECISE so that no compiler
// fuses a multiply-add (scenes/groom.cpp is built with -ffp-contract=off for the
// same reason). What needs more (cosines, lengths) the CPU works out once into
// the rule's inputs.
#ifndef SB_GROOM_RULE_H
#define SB_GROOM_RULE_H

#include "base/hash.h"

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace sb::groom_rule {
using uint = uint32_t;
using glm::vec3;
using glm::vec4;
#define SB_PRECISE
#define SB_RULE_FN inline
#else
#define SB_PRECISE precise
#define SB_RULE_FN
#endif

// Neighbouring guides each guide keeps (scenes/groom.cpp: nearest roots first).
#define SB_GROOM_NEIGHBOURS 3u

// The project's integer hash (base/hash.h), the same in both languages.
SB_RULE_FN uint groomHash(uint x) { return hash32(x); }

// Uniform in [0, 1): the top 24 bits, exact in a float.
SB_RULE_FN float groomUnit(uint h) { return float(h >> 8u) * (1.0f / 16777216.0f); }

// A rendered strand's seed: the instance's seed and the strand's index.
SB_RULE_FN uint groomStrandSeed(uint instanceSeed, uint strand) {
  return groomHash(instanceSeed ^ groomHash(strand + 0x9e3779b9u));
}

// The seed of point j's noise.
SB_RULE_FN uint groomPointSeed(uint seed, uint j) {
  return groomHash(seed + (j + 1u) * 0x27d4eb2du);
}

// Which of the home guide's neighbours the strand leans towards.
SB_RULE_FN uint groomNeighbourSlot(uint seed) { return groomHash(seed ^ 1u) % SB_GROOM_NEIGHBOURS; }

// The weight of that neighbour: [0, spread/2), so the home guide leads.
SB_RULE_FN float groomWeight(uint seed, float spread) {
  SB_PRECISE float w = groomUnit(groomHash(seed ^ 2u)) * spread * 0.5f;
  return w;
}

// A vector in [-scale/2, scale/2)^3 from three hashes of `seed`.
SB_RULE_FN vec3 groomJitter(uint seed, float scale) {
  SB_PRECISE vec3 u = vec3(groomUnit(groomHash(seed ^ 0x68e31da4u)) - 0.5f,
                           groomUnit(groomHash(seed ^ 0xb5297a4du)) - 0.5f,
                           groomUnit(groomHash(seed ^ 0x1b56c4e9u)) - 0.5f);
  SB_PRECISE vec3 r = u * scale;
  return r;
}

// Point j of a rendered strand: between its home guide's point `home` and its
// neighbour's `other` (weight w), moved by the strand's offset, pulled back to
// the home guide by the clumping (clump * along, along = j / (points - 1): none at
// the root, most at the tip), and moved by the point's noise (growing along it).
SB_RULE_FN vec3 groomPoint(vec3 home, vec3 other, float w, vec3 offset, float clump, float along,
                           vec3 noise) {
  SB_PRECISE vec3 between = home + (other - home) * w + offset;
  SB_PRECISE float pull = clump * along;
  SB_PRECISE vec3 clumped = between + (home - between) * pull;
  SB_PRECISE vec3 p = clumped + noise * along;
  return p;
}

// An instance's placement: a turn about +y (cosine, sine in place.xy) and a
// move in the floor plane (place.zw: x, z).
SB_RULE_FN vec3 groomPlace(vec3 p, vec4 place) {
  SB_PRECISE float x = place.x * p.x - place.y * p.z + place.z;
  SB_PRECISE float z = place.y * p.x + place.x * p.z + place.w;
  return vec3(x, p.y, z);
}

// Level of detail (docs/geometry.md): an instance keeps `kept` of its `strands`
// strands (the CPU chose how many, from a share or its size on screen). Strand
// i's home guide is i mod guides, so the strands come in rows of `guides`, one
// follower of each guide. An instance keeps its first kept / guides rows whole
// and, of the row it cuts short, the guides first in the groom's guide order
// (a shuffle: a cut row is spread over the groom, not its first guides). The
// t-th kept strand (t < kept) is t below the cut row `row` this gives, and
// row + order[t - row] from it on; `row` is `strands` where no whole row is cut
// (kept a whole number of rows, or into the short last row, kept in order).
// So the kept strands depend on integers only, and fewer kept are always a
// subset of more (no strand comes and goes as the share changes).
SB_RULE_FN uint groomLodCutRow(uint kept, uint strands, uint guides) {
  uint row = kept / guides * guides;
  return row + guides <= strands && row < kept ? row : strands;
}

// A point's thickness: the home guide's, widened for the strands the level of
// detail left out (widen = strands / kept, the instance's, from the CPU).
SB_RULE_FN float groomThickness(float guide, float widen) {
  SB_PRECISE float t = guide * widen;
  return t;
}

// The colour's alpha the renderer uploads: the scene's opacity times the
// guide's (HAIR semantics: transparency 0 = opaque).
SB_RULE_FN float groomAlpha(float hairAlpha, float transparency) {
  SB_PRECISE float a = hairAlpha * (1.0f - transparency);
  return a;
}

#ifdef __cplusplus
}  // namespace sb::groom_rule
#endif

#endif  // SB_GROOM_RULE_H
