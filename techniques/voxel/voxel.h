#pragma once

#include "base/options.h"
#include "render/common/opaque_shadow.h"
#include "render/common/technique.h"

namespace sb {

// Voxelized hair density, as Unreal's hair strands voxelization (and vkhr's
// density volume) do it: one hair pass from the light splats every fragment
// into a volume of uint counters (a storage buffer, atomic adds; x and y
// follow the light map, min(grid, size) columns per side so that a column is
// never narrower than a map texel; z cuts the hair's depth range from the
// light into grid slices), and the lookup marches from the point towards the
// light through the volume (techniques/voxel/voxel_math.glsl):
// V = exp(-density_scale w n), n the marched hair count, w = -ln(1 - alpha).
// Memory: columns^2 x grid x 4 bytes (grid^3 x 4 for size >= grid), whatever
// the hair. Visibility never rises along a light ray (the march's partial
// step is linear in depth).
class VoxelDensityShadow : public LightMapShadow {
 public:
  struct Options {
    uint32_t grid = 128;
    uint32_t steps = 128;
    float densityScale = 1.0f;
    uint32_t size = 512;
    float bias = 0.002f;
  };
  explicit VoxelDensityShadow(const Options& o) : opt_(o) {}
  std::string name() const override { return "voxel"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  ShadowLookup lookup() const override;
  std::vector<Counter> counters(Device& dev) override;

 private:
  Pass splatPass() const;
  uint32_t columns() const { return std::min(opt_.grid, opt_.size); }

  Options opt_;
  Buffer params_, grid_;
  Pipeline pipeline_;
};

}  // namespace sb
