#pragma once

#include "base/options.h"
#include "render/common/opaque_shadow.h"
#include "render/common/technique.h"
#include "techniques/rt/tier.h"

namespace sb {

// Ray-traced strand shadows: every strand segment is a capsule's cylinder of
// radius r (rt_math.glsl says how a ray hits it); rays from the shaded point
// to the light find the segments they may cross in one of two tiers: the
// software tier walks a BVH built on the CPU at setup (techniques/rt/bvh.h) in
// shader code (lookup.glsl), the ray-query tier (Vulkan devices with
// VK_KHR_ray_query) asks a ray query over an acceleration structure of the
// segments' boxes (lookup_ray_query.glsl); both judge each candidate by the
// same rule (rays.glsl). tier=auto takes ray queries where the device has them.
// The width: a strand is as wide as the light map draws it, one texel for
// lines and ribbon_width texels for ribbons of a map of `size` texels, so
// r = width / 2 texels, in world units at the segment's midpoint (constant
// for a directional light). That is the width the exact reference and the
// anti-aliased reference give strands in shadow, so the three judge one
// geometry. Opacity: the scene's shadow_alpha per strand crossed, as exact.
class RayTracedShadow : public LightMapShadow {
 public:
  struct Options {
    uint32_t size = 512;
    float bias = 0.002f;
    uint32_t rays = 1;
    uint32_t maxHits = 0;
    rt::TierOptions walk;  // tier= and bvh= (techniques/rt/tier.h)
  };
  explicit RayTracedShadow(const Options& o) : opt_(o) {}
  std::string name() const override { return "rt"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  ShadowLookup lookup() const override;
  std::vector<Counter> counters(Device& dev) override;
  std::string tier() const override { return rayQuery_ ? "ray_query" : "software"; }
  std::string tierReason() const override { return tierReason_; }

 private:
  Pass clearPass() const;

  Options opt_;
  bool rayQuery_ = false;   // the tier in use (after setup)
  std::string tierReason_;  // why (rt::chooseTier)
  Buffer params_, status_;
  rt::WalkBuffers walk_;  // the tier's BVH or acceleration structure, and the segments
  double buildMs_ = 0;
  uint32_t nodeCount_ = 0, depth_ = 0, segmentCount_ = 0;
};

}  // namespace sb
