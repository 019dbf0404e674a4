// The groom's strands made on the GPU: one invocation per rendered point (of
// the strands the level of detail kept), by the rule the CPU runs
// (scenes/groom_rule.h), into the buffers every technique reads
// (common/bindings.glsl): point g * points + j of strand g, and the
// segment g * (points - 1) + j starting there, as the CPU path uploads them.
#include "../common/invocation.glsl"
#include "../../scenes/groom_rule.h"
#include "../common/slots.h"
#include "slots.h"
#include "uniforms.h"
layout(local_size_x = 64) in;
layout(std430, binding = SB_SLOT_POINTS) writeonly buffer Points { vec4 points[]; };
layout(std430, binding = SB_SLOT_COLORS) writeonly buffer Colors { vec4 colors[]; };
layout(std430, binding = SB_SLOT_SEGMENTS) writeonly buffer Segments { uint segments[]; };
layout(std430, binding = SB_SLOT_GEN_GUIDE_POINTS) readonly buffer GuidePoints {
  vec4 guidePoints[];
};
layout(std430, binding = SB_SLOT_GEN_GUIDE_COLORS) readonly buffer GuideColors {
  vec4 guideColors[];
};
layout(std430, binding = SB_SLOT_GEN_NEIGHBOURS) readonly buffer Neighbours { uint neighbours[]; };
layout(std430, binding = SB_SLOT_GEN_PLACEMENTS) readonly buffer Placements { vec4 placements[]; };
layout(std430, binding = SB_SLOT_GEN_SEEDS) readonly buffer Seeds { uint seeds[]; };
layout(std430, binding = SB_SLOT_GEN_LODS) readonly buffer Lods { uvec4 lods[]; };
layout(std430, binding = SB_SLOT_GEN_GUIDE_ORDER) readonly buffer GuideOrder {
  uint guideOrder[];
};

// The instance whose kept strands hold strand g: the last whose first is <= g
// (every instance keeps at least one strand).
uint instanceOf(uint g) {
  uint lo = 0u, hi = genSizes.w - 1u;
  while (lo < hi) {
    uint mid = (lo + hi + 1u) / 2u;
    if (lods[mid].x <= g) lo = mid;
    else hi = mid - 1u;
  }
  return lo;
}

void main() {
  uint at = linearInvocation();
  if (at >= genTotal.x) return;
  uint perStrand = genSizes.y, strands = genSizes.z;
  uint strand = at / perStrand, j = at - strand * perStrand;
  uint instance = instanceOf(strand);
  uvec4 lod = lods[instance];  // first, kept, widen's bits
  uint t = strand - lod.x, row = groomLodCutRow(lod.y, strands, genSizes.x);
  uint i = t < row ? t : row + guideOrder[t - row];
  uint seed = groomStrandSeed(seeds[instance], i);
  uint home = i % genSizes.x;
  uint other = neighbours[home * SB_GROOM_NEIGHBOURS + groomNeighbourSlot(seed)];
  float w = groomWeight(seed, genRule.x);
  vec3 offset = groomJitter(seed, genRule.y);
  vec4 h = guidePoints[home * perStrand + j];
  vec4 o = guidePoints[other * perStrand + j];
  vec3 noise = groomJitter(groomPointSeed(seed, j), genRule.z);
  precise float along = float(j) * genMore.x;
  vec3 p = groomPoint(h.xyz, o.xyz, w, offset, genRule.w, along, noise);
  vec4 c = guideColors[home * perStrand + j];
  points[at] = vec4(groomPlace(p, placements[instance]),
                    groomThickness(h.w, uintBitsToFloat(lod.z)));
  colors[at] = vec4(c.rgb, groomAlpha(genMore.y, c.w));
  if (j + 1u < perStrand) segments[strand * (perStrand - 1u) + j] = at;
}
