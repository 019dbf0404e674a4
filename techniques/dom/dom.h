#pragma once

#include "base/options.h"
#include "render/common/opaque_shadow.h"
#include "render/common/technique.h"

namespace sb {

// Deep opacity maps (Yuksel & Keyser 2008): a depth map of the hair from the
// light (a depth-only pass, the paper's first step) gives each texel the depth
// z0 where its hair begins; K opacity layers [z0 + d_(k-1), z0 + d_k) follow
// the hair's shape. One hair pass accumulates every fragment into its layer
// and all layers behind it (additive blending); K = 4n - 1 layers are packed
// in the n RGBA layers of one texture array (channel 0 of layer 0, where the
// slides keep z0, is unused: z0 is read from the depth map), each layer a
// render target.
// The lookup interpolates within the point's layer and returns
// (1 - alpha_s)^opacity.
class DeepOpacityMaps : public LightMapShadow {
 public:
  struct Options {
    uint32_t layers = 3;
    int spacing = 1;          // kDomConstant | kDomLinear | kDomPow2 | kDomFibonacci | kDomPower
    int filter = 0;           // kFilterNone | kFilterPcf2x2 | kFilterPcf6x4 | kFilterPcf6x6
    std::string listText;     // spacing=list: the sizes as given ("1;2;3")
    std::vector<float> list;  // spacing=list: layer sizes as multiples of s
    float sizeAbs = 0.0f;     // layer size s in light depth units (0: use sizeFrac)
    float sizeFrac = 0.1f;    // s as a fraction of the hair's depth range from the light
    int beyond = 1;           // kDomIgnore | kDomLast | kDomExtend
    uint32_t depthBits = 32;  // z0 quantized to 8, 16 or 32 bits where it is read
    bool thesisCounting = false;  // counting=thesis: own and preceding layers (Listing 3)
    uint32_t size = 512;
    float bias = 0.002f;
  };
  static constexpr uint32_t kMaxLayers = 31;  // 8 targets: the colour attachments a pass may have

  static constexpr int kSpacingList = -1;  // spacing=list, until finish() reads the list
  // The registry's options after their table filled them: the list read, layers matched.
  static void finish(Options& o);
  explicit DeepOpacityMaps(const Options& o) : opt_(o) {}
  std::string name() const override { return "dom"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  ShadowLookup lookup() const override;

  const std::vector<float>& boundaries() const { return d_; }
  uint32_t targets() const { return (opt_.layers + 4) / 4; }  // layers of the array
  Pass depthPass() const;  // depth-only: a depth attachment, no colour targets

 private:
  Pass opacityPass() const;

  Options opt_;
  std::vector<float> d_;
  Texture depth_;
  Texture maps_;  // RGBA32F array of targets() layers
  Buffer params_;
  Pipeline depthPipeline_, opacityPipeline_;
};

}  // namespace sb
