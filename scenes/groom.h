// A groom: guide strands and the rule that makes the rendered strands from them
// (scenes/groom_rule.h, shared with the GPU's compute pass), repeated over a crowd
// of instances. Scene data: a scene made with guides= or instances= (every scene
// has them) keeps its groom next to the strands the rule made on the CPU, so the
// CPU path, every reference and the exact ground truth draw exactly the strands
// the GPU makes from the same groom (render --geometry compute).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace sb {

struct Strands;

struct GroomSettings {
  uint32_t guideEvery = 0;  // every n-th strand is a guide; 0: every strand, and no variation
  uint32_t instances = 1;
  uint32_t seed = 1;
  float spread = 0.5f;  // how far a strand leans towards a neighbouring guide (0..1)
  float offset = 0.5f;  // per-strand offset, in mean guide spacings
  float noise = 0.1f;   // per-point noise at the tip, in mean guide spacings
  float clump = 0.0f;   // pull towards the home guide at the tip (0..1)
  // Level of detail (groomLevelOfDetail): a share of each instance's strands
  // kept (lod < 1), or a share by the instance's size on screen (lodPixels > 0).
  float lod = 1.0f;
  float lodPixels = 0;
};

// What the level of detail kept of one instance: its kept strands are strands
// first .. first + kept - 1 of the groom's, widened by widen = strands / kept.
// The generation pass reads it as a uvec4 (widen's bits in z).
struct GroomInstanceLod {
  uint32_t first = 0, kept = 0;
  float widen = 1;
  uint32_t unused = 0;
};

struct Groom {
  // Guides: guideCount strands of `points` points each (resampled to the longest
  // guide's count where they differ), strand-major.
  uint32_t guideCount = 0, points = 0;
  std::vector<glm::vec4> guidePoints;  // xyz, thickness
  std::vector<glm::vec4> guideColors;  // rgb, transparency (HAIR semantics)
  // SB_GROOM_NEIGHBOURS per guide: the guides with the nearest roots (itself when alone).
  std::vector<uint32_t> neighbours;
  uint32_t strands = 0;  // rendered strands per instance
  // Per instance: its seed and its placement (cosine, sine of the turn about +y;
  // x, z of the move): groom_rule.h's groomPlace.
  std::vector<uint32_t> instanceSeeds;
  std::vector<glm::vec4> placements;
  // The rule's scalars, world units where they are lengths.
  float spread = 0, offset = 0, noise = 0, clump = 0;
  float alongStep = 0;  // 1 / (points - 1): j * alongStep is how far along point j is
  // Level of detail: the settings, one instance's bounding sphere (before its
  // placement, which turns it about its centre), the guides in the order a
  // row cut short keeps them (groom_rule.h: groomLodCutRow) and, per instance,
  // what groomLevelOfDetail kept (all of it until then).
  float lod = 1, lodPixels = 0;
  glm::vec3 centre{0};
  float radius = 0;
  std::vector<uint32_t> guideOrder;
  std::vector<GroomInstanceLod> lods;

  bool empty() const { return guideCount == 0; }
  bool hasLod() const { return lod < 1.0f || lodPixels > 0; }
  uint32_t instanceCount() const { return static_cast<uint32_t>(placements.size()); }
  uint64_t fullStrands() const { return uint64_t(strands) * instanceCount(); }
  // The strands made: those the level of detail kept.
  uint64_t totalStrands() const {
    return lods.empty() ? 0 : uint64_t(lods.back().first) + lods.back().kept;
  }
  uint64_t totalPoints() const { return totalStrands() * points; }
};

// The groom of `strands` (a scene's, after scale and zero_segments): its guides
// (strands of fewer than 2 points are left out), their neighbours, the crowd's
// placements on a grid in the floor plane (spacing from the strands' extent).
// Throws InputError when nothing is left to guide or the crowd is too large.
Groom makeGroom(const Strands& strands, const GroomSettings& settings);

// The level of detail for a view (docs/geometry.md): with lod < 1 every
// instance keeps round(lod * strands); with lodPixels = P an instance whose
// bounding sphere spans s pixels across the image's height keeps
// min(1, (s / P)^2) of its strands (the strands per pixel of screen held at
// what they were at P pixels). At least one strand each; the kept strands are
// widened by strands / kept. Without either, all are kept. Sets groom.lods.
struct Camera;
void groomLevelOfDetail(Groom& groom, const Camera& camera, uint32_t imageHeight);

// The rule run on the CPU over every instance's kept strands: the t-th kept
// strand of instance k is strand g = lods[k].first + t, its point j at
// g * points + j (the layout the compute pass writes too).
Strands generateStrands(const Groom& groom);

}  // namespace sb
