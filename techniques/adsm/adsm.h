#pragma once

#include "base/options.h"
#include "render/common/opaque_shadow.h"
#include "render/common/technique.h"

namespace sb {

// Approximated deep shadows as engines ship them (TressFX 1.0-3.x, Tomb
// Raider 2013): a single depth map of the hair's front from the light, and a
// fiber count estimated from a point's distance behind that front,
// dz / (spacing x radius), turned into visibility (1 - alpha)^fibers and
// averaged over a Gaussian PCF kernel (techniques/adsm/adsm_math.glsl). One
// hair pass and one R32 map: the cheapest of the opacity techniques, and the
// error grows where the hair is not evenly packed (a stray strand in front of
// a clump darkens everything behind it as if the gap were full of hair).
// The fiber radius is half the scene's mean strand thickness.
class ApproximatedDeepShadows : public LightMapShadow {
 public:
  struct Options {
    float spacing = 4.0f;  // fiber spacing, in fiber radii
    uint32_t kernel = 5;   // taps per side of the PCF kernel (TressFX: 5)
    uint32_t size = 512;
    float bias = 0.002f;
  };
  explicit ApproximatedDeepShadows(const Options& o) : opt_(o) {}
  std::string name() const override { return "adsm"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  ShadowLookup lookup() const override;
  std::vector<Counter> counters(Device& dev) override;

 private:
  Pass depthPass() const;

  Options opt_;
  Texture depth_;
  Buffer params_;
  Pipeline pipeline_;
  float radius_ = 0.0f, worldPerDepth_ = 0.0f;
};

}  // namespace sb
