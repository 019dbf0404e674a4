// The two tiers of the ray-traced techniques (--shadow rt and --oit rt), in
// one place: their options (bvh=, tier=), the choice of tier on a device
// (tier=auto takes ray queries where a GPU offers them, and the software tier
// on a CPU device, where ray queries run in shader code and are far slower;
// tier=ray_query is bad input where the device has none), and the data each
// tier's walk reads. The
// software tier walks a BVH built here on the CPU (bvh.h) in shader code; the
// ray-query tier asks ray queries over an acceleration structure of the
// segments' boxes (Device::createAccelerationStructure), box i segment i.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "backends/device.h"
#include "base/options.h"
#include "render/common/technique.h"
#include "techniques/rt/bvh.h"

namespace sb::rt {

enum class Tier { Auto, Software, RayQuery };

struct TierOptions {
  Tier tier = Tier::Auto;
  bool sah = true;  // BVH splits: binned SAH, or at the median
};

// bvh= and tier=, declared once for both techniques (opt::nested binds them to
// their Options' TierOptions member), after each technique's own options.
std::vector<Option<TierOptions>> tierOptions();

// Whether `technique` ("shadow technique 'rt'") traces with ray queries on
// this device, and why (the render JSON's tier_reason); tier=ray_query without
// them is an InputError saying why.
struct TierChoice {
  bool rayQuery = false;
  std::string reason;
};
TierChoice chooseTier(Tier tier, const DeviceInfo& info, const std::string& technique);

// The scene's segments, index i segment i, each `width` units wide at its midpoint, one unit
// being `worldPerUnitPerW` world units per unit of clip w under `viewProj` (a pixel of the
// frame, a texel of a light map: the width the raster draws there). A segment whose points lie
// past the point buffer is left degenerate (radius 0: never hit).
std::vector<Segment> sceneSegments(Device& dev, const GpuScene& scene, const glm::mat4& viewProj,
                                   float worldPerUnitPerW, float width);

// What a tier's walk reads, built on the CPU: the software tier's BVH and its
// segments in BVH order, or for ray queries the segments in scene order (an
// identity order, no nodes) and one box each. packed is packSegments' layout.
struct Walk {
  Bvh bvh;
  std::vector<glm::vec4> packed;
  std::vector<std::array<glm::vec3, 2>> boxes;  // ray queries only: at least one
  double buildMs = 0;                           // the CPU's time to build the above
};
Walk buildWalk(const std::vector<Segment>& segs, bool rayQuery, bool sah);

// The walk on the device, named `prefix` + "bvh_nodes", "segments", "boxes",
// "acceleration_structure" (the latter two for ray queries, the first for the
// software tier), owned by `owner`.
struct WalkBuffers {
  Buffer nodes, segments, boxes, scene;
};
WalkBuffers uploadWalk(Device& dev, const Walk& w, bool rayQuery, const std::string& prefix,
                       Owner owner);

}  // namespace sb::rt
