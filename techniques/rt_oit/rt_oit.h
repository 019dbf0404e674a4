// Ray-traced transparency (--oit rt): a primary ray per pixel through the
// centre of the pixel into the strand segments as the camera sees them, its
// hits composited front to back in depth order over the opaque result; each
// hit is shaded with the scene's shading model and shadow technique
// (trace.comp says how). The segments are found in one of rt's two tiers
// (techniques/rt/tier.h): the software tier walks a BVH built on the CPU at
// setup (techniques/rt/bvh.h) in the shader, the ray-query tier (Vulkan
// devices with VK_KHR_ray_query) asks ray queries over an acceleration
// structure of the segments' boxes; both judge each candidate by the same
// test, so they collect the same hits. tier=auto takes ray queries where the
// device has them.
// The width: a segment is a capsule's cylinder (rt_math.glsl) of radius half
// the strand's drawn width (lines 1 pixel, ribbons ribbon_width pixels) in
// world units at the segment's midpoint, the width the raster techniques draw.
// A ray at the pixel centre then sees the strand's true width, as the
// anti-aliased reference does at each of its samples, where the exact
// reference sees what the rasterizer covers (docs/transparency-techniques.md).
#pragma once

#include "render/common/hair_oit.h"
#include "techniques/rt/tier.h"

namespace sb {

class OptionReader;

class RayTracedOit : public CompositedOit {
 public:
  struct Options {
    uint32_t k = 0;        // 0: every hit in order; k: the k nearest, the rest merged
    uint32_t maxHits = 0;  // k = 0: hits composited per pixel at most (0: no cap)
    rt::TierOptions walk;  // tier= and bvh= (techniques/rt/tier.h)
  };
  static constexpr uint32_t kMaxK = 32;
  static constexpr uint32_t kMaxSegments = 1u << 24;
  explicit RayTracedOit(Options o) : o_(o) {}
  static void check(Options& o);  // between options, after the registry read them
  std::string name() const override { return "rt"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const HairShading& shading, const OitTargets& targets) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  std::vector<Counter> counters(Device& dev) override;
  std::vector<std::string> warnings(Device& dev) override;
  std::string tier() const override { return rayQuery_ ? "ray_query" : "software"; }
  std::string tierReason() const override { return tierReason_; }

 private:
  Pass tracePass() const;

  Options o_;
  bool rayQuery_ = false;   // the tier in use (after setup)
  std::string tierReason_;  // why (rt::chooseTier)
  Buffer params_, status_;
  rt::WalkBuffers walk_;  // the tier's BVH or acceleration structure, and the segments
  Pipeline trace_;
  double buildMs_ = 0;
  uint32_t nodeCount_ = 0, depth_ = 0, segmentCount_ = 0;
};

}  // namespace sb
