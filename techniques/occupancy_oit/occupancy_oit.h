#pragma once

#include "render/common/hair_oit.h"
#include "render/common/technique.h"
#include "techniques/occupancy/occupancy_maps.h"

namespace sb {

class OptionReader;

// Occupancy-ordered blending (--oit occupancy; Sintorn & Assarsson 2009,
// section 3.4): the occupancy machinery of the shadow version
// (techniques/occupancy) built from the eye, then one additive pass in which
// every hair fragment weights its colour by (1 - a)^o for its estimated order
// o, and a resolve with the paper's Lambda renormalisation. Passes, all hair
// passes depth-tested against the opaque depth without writing it:
//   occupancy_oit.depth_range  nearest/furthest fragment per pixel (RG32F, min)
//   occupancy_oit.occupancy    one bit per slice (RGBA32UI array, a layer per 128, logic-op OR)
//   occupancy_oit.slabs        fragment count per slab (RGBA32F array, a layer per 4, additive)
//   occupancy_oit.accumulate   (1 - a)^o a (c, 1) into RGBA32F and log2(1 - a)
//                              into R32F (additive, fp32)
//   occupancy_oit.resolve      hair over the opaque colour
class OccupancyOit : public KeptInputsOit {
 public:
  struct Options {
    uint32_t slices = 128;  // multiple of 32, at most 1024
    uint32_t slabs = 4;     // divides slices, at most 32
    bool lambda = true;     // the paper's renormalisation of the hair weights
    int order = 0;          // 0 corrected (oitOrder), 1 paper (oitOrderPaper), 2 printed
                            // (oitOrderPrinted, with Lambda as printed: oitResolvePrinted)
  };
  // Reads and validates slices, slabs, lambda (InputError).
  static void check(Options& o);  // between options, after the registry read them
  explicit OccupancyOit(const Options& opts) : opts_(opts) {}

  std::string name() const override { return "occupancy"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const HairShading& shading, const OitTargets& targets) override;
  void addPasses(FrameGraph& graph, Device& dev) override;

  // The eye-space maps and accumulation targets, for tests.
  Texture rangeMap() const { return maps_.range(); }
  Texture bitMap() const { return maps_.bits(); }    // RGBA32UI array
  Texture slabMap() const { return maps_.slabs(); }  // RGBA32F array
  Texture accumulation() const { return accum_; }
  Texture log2Transmittance() const { return log2T_; }

 private:
  Pass accumulatePass() const;
  Pass resolvePass() const;

  Options opts_;
  OccupancyMaps maps_;
  Texture accum_, log2T_;
  Pipeline accumPipeline_, resolvePipeline_;
};

}  // namespace sb
