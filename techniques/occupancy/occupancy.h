#pragma once

#include "render/common/opaque_shadow.h"
#include "render/common/technique.h"
#include "techniques/occupancy/occupancy_maps.h"

namespace sb {

class OptionReader;

// Occupancy maps (Sintorn & Assarsson 2009). Three passes over the hair from
// the light: a depth-range map (nearest and furthest fragment per texel, RG32F,
// min blending), an occupancy map (one bit per slice of that range, RGBA32UI,
// logic-op OR) and a slab map (fragment count per group of slices, RGBA32F,
// additive). The lookup spreads slab i's F_i fragments over its S_i set bits
// and interpolates linearly within a slice (occupancy_math.glsl).
class OccupancyShadow : public ShadowTechnique {
 public:
  struct Options {
    uint32_t size = 512;
    float bias = 0.002f;
    uint32_t slices = 128;  // multiple of 32, at most 1024 (8 RGBA32UI layers)
    uint32_t slabs = 4;     // divides slices, at most 32; 4 per RGBA32F layer
    bool slabMap = true;    // false: every set bit counts as one fragment
    // slab_map=count, the paper's occupancy-only variant (section 3.1): each
    // set bit counts F / S, F the texel's fragment count (a count map of one
    // slab), S its set bits.
    bool countOnly = false;
    enum class SlabMap { On, Off, Count } slabMapChoice = SlabMap::On;  // slab_map=, for finish
    bool jitter = false;         // half-texel jitter of the lookup (the paper's anti-aliasing)
    uint32_t jitterSamples = 1;  // jittered lookups averaged (jitter=on)
  };
  // Reads and validates size, bias, slices, slabs, slab_map, jitter (InputError).
  static void finish(Options& o);  // slab_map= applied, rules between options
  explicit OccupancyShadow(const Options& opts) : opts_(opts) {}

  std::string name() const override { return "occupancy"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  ShadowLookup lookup() const override;

  // The maps, for tests: depth range (RG32F), occupancy bits (an RGBA32UI
  // array), slab counts (an RGBA32F array; none with slab_map=off).
  Texture rangeMap() const { return maps_.range(); }
  Texture bitMap() const { return maps_.bits(); }
  Texture slabMap() const { return maps_.slabs(); }

 private:
  Options opts_;
  Buffer lightView_, params_;
  OccupancyMaps maps_;
  OpaqueShadow opaque_;
};

}  // namespace sb
