// The occupancy machinery of Sintorn & Assarsson (2009), built once for two
// uses: occupancy maps (from the light, techniques/occupancy) and
// occupancy-ordered blending (from the eye, techniques/occupancy_oit). Three
// passes over the hair:
//   <prefix>.depth_range  nearest/furthest fragment per pixel (RG32F, min of (z, -z))
//   <prefix>.occupancy    one bit per slice of that range (an RGBA32UI array, a layer
//                         per 128 slices, each layer a target; logic-op OR)
//   <prefix>.slabs        fragment count per slab (an RGBA32F array, a layer per 4
//                         slabs; additive); optional
#pragma once

#include <algorithm>

#include "render/common/technique.h"
#include "techniques/occupancy/slots.h"

namespace sb {

class OccupancyMaps {
 public:
  struct Config {
    std::string prefix;         // names of passes and textures
    Owner owner = Owner::None;  // memory owner of the textures
    uint32_t width = 0, height = 0;
    uint32_t slices = 128, slabs = 4;  // at most kMaxSlices, kMaxSlabs
    bool slabMap = true;
    // From the light: slices in light distance (light_pass_depth.glsl; linear
    // for point lights); from the eye: window depth.
    bool lightDistance = false;
    // From the eye: the opaque depth the hair is tested against (none from
    // the light), cleared by the first pass when nothing opaque was drawn.
    Texture depth;
    bool clearDepth = false;
  };
  // Where occupancy.frag/slabs.frag read the range.
  static constexpr uint32_t kRangeBinding = SB_SLOT_OCC_RANGE;
  // One colour attachment per layer, and a pass may have 8 (the least GL
  // guarantees): 8 RGBA32UI layers of 128 slices, 8 RGBA32F layers of 4 slabs.
  static constexpr uint32_t kMaxSlices = 1024, kMaxSlabs = 32;

  // defs: SB_OCC_* for the shaders (see occupancyDefines()).
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s, Buffer viewUbo,
             const Config& config);
  void addPasses(FrameGraph& graph, Device& dev);

  uint32_t wordTargets() const { return (config_.slices + 127) / 128; }  // layers of bits()
  uint32_t slabTargets() const { return config_.slabMap ? (config_.slabs + 3) / 4 : 0; }
  // SB_OCC_SLICES, _SLABS, _WORD_TARGETS, _SLAB_TARGETS, _MAX_WORDS, _MAX_SLABS
  ShaderDefines defines() const;
  // What the shaders read from the layers: 4 words (128 slices) and 4 slabs per texel.
  uint32_t maxWords() const { return 4 * wordTargets(); }
  uint32_t maxSlabs() const { return std::max(4 * slabTargets(), 1u); }
  Texture range() const { return range_; }
  Texture bits() const { return bits_; }    // RGBA32UI, wordTargets() layers
  Texture slabs() const { return slabs_; }  // RGBA32F, slabTargets() layers; none without
  std::vector<Texture> maps() const;        // range, bits and slabs (if any)

 private:
  Pass hairPass(const std::string& step, bool first) const;
  Pass rangePass() const;
  Pass bitsPass() const;
  Pass slabsPass() const;

  Config config_;
  const GpuScene* scene_ = nullptr;
  RenderSettings settings_;
  Buffer viewUbo_;
  Texture range_, bits_, slabs_;
  Pipeline rangePipeline_, bitsPipeline_, slabsPipeline_;
};

}  // namespace sb
