#pragma once

#include "base/options.h"
#include "render/common/opaque_shadow.h"
#include "render/common/technique.h"

namespace sb {

// Fourier opacity maps (Jansen & Bavoil 2010): per light texel, the
// absorption along the light ray as a truncated Fourier series over the
// hair's depth range (techniques/fom/fom_math.glsl), accumulated by additive
// blending in one hair pass per 8 targets (2n + 1 floats, 4 per layer of one
// RGBA32F texture array); the lookup integrates the series up to the point and
// clamps exp(-I) to [0, 1] (the paper's answer to ringing). Not monotone
// along a light ray: the ringing the clamping bounds but does not remove.
class FourierOpacityMaps : public LightMapShadow {
 public:
  struct Options {
    uint32_t coefficients = 8;  // frequencies n: a_0 and n (a_k, b_k) pairs
    uint32_t size = 512;
    float bias = 0.002f;
  };
  static constexpr uint32_t kMaxCoefficients = 31;  // 63 floats: 16 layers, 2 passes

  explicit FourierOpacityMaps(const Options& o) : opt_(o) {}
  std::string name() const override { return "fom"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  ShadowLookup lookup() const override;

  uint32_t layers() const { return (2 * opt_.coefficients + 1 + 3) / 4; }

 private:
  Pass accumulatePass(uint32_t first, uint32_t count) const;

  Options opt_;
  Texture maps_;
  Buffer params_;
  std::vector<Pipeline> pipelines_;  // one per 8 layers
};

}  // namespace sb
