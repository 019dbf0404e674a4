#pragma once

#include "base/options.h"
#include "render/common/opaque_shadow.h"
#include "render/common/technique.h"

namespace sb {

// Moment shadow maps for semi-transparent occluders: the shadow variant of
// moment-based OIT (Muenstermann et al. 2018, section 6; Peters & Klein 2015's
// moment shadow mapping with additive moments). One light pass adds, per
// light texel, the absorbance A = -ln(1 - alpha) of every hair fragment to b0
// and A times its power or trigonometric moments of depth to 4, 6 or 8 more
// floats (additive blending into RGBA32F targets); the lookup reconstructs the
// transmittance in front of the receiver's depth with mboit's math
// (techniques/mboit/mboit_math.glsl: one moment library for both).
class MomentShadowMaps : public LightMapShadow {
 public:
  struct Options {
    int moments = 6;      // 4, 6 or 8 real moments beyond b0
    bool trig = false;    // trigonometric instead of power moments
    uint32_t size = 512;  // map size
    float bias = 0.002f;  // lookup depth bias (light window depth)
  };
  explicit MomentShadowMaps(const Options& o) : opt_(o) {}
  std::string name() const override { return "msm"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  ShadowLookup lookup() const override;
  std::vector<Counter> counters(Device& dev) override;
  // The reconstruction interpolates between two bounds that are monotone in
  // exact arithmetic, but in fp32 at the absorbance of dense hair (b0 in the
  // hundreds) it is not: measured on straight hair, visibility 0.031 then 1
  // one probe step further from the light. Not promised (msm/unit.cpp: monotone = false).

 private:
  Pass accumulatePass() const;
  bool highTarget() const { return opt_.moments > 4; }

  Options opt_;
  Texture b0_, low_, high_;
  Buffer params_;
  Pipeline pipeline_;
};

}  // namespace sb
