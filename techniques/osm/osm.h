#pragma once

#include "base/options.h"
#include "render/common/opaque_shadow.h"
#include "render/common/technique.h"

namespace sb {

// Opacity shadow maps (Kim & Neumann 2001): n planar maps perpendicular to
// the light, each holding the opacity (fragment count) of the hair in front
// of its depth D_i; a point's opacity is interpolated linearly between the
// two maps enclosing it, and its visibility is (1 - alpha_s)^n.
//
// Maps are packed 4 per RGBA texel group; groups are tiles of a few atlases,
// the layers of one texture array, rendered by pointing the light's
// projection at a tile and discarding outside it. passes=single draws the
// hair once per map (the original); passes=multi draws it once per tile row
// of up to 6 render targets (atlas layers) x 4 channels.
class OpacityShadowMaps : public LightMapShadow {
 public:
  struct Options {
    uint32_t maps = 16;
    int slicing = 0;  // kOsmUniform | kOsmDensity | kOsmGamma (slicing.glsl)
    float gamma = 2.0f;
    bool multi = true;
    uint32_t bits = 32;  // 8 (RGBA8 unorm), 16 (RGBA16F), 32 (RGBA32F)
    float kappa = 0.0f;  // 8 bits: e^-kappa = 2^-8 when 0 (the paper's choice)
    uint32_t size = 512;
    float bias = 0.002f;
    int filter = 0;  // kFilterNone | kFilterPcf2x2 | kFilterPcf6x4 | kFilterPcf6x6
  };
  // Atlases (layers) per multi pass. A pass may have 8 targets, but more
  // atlases would lay the maps out differently and change today's images.
  static constexpr uint32_t kMaxTargets = 6;
  static constexpr uint32_t kMaxAtlasSize = 16384;

  // How the maps are laid out; throws InputError when they cannot fit.
  struct Layout {
    uint32_t groups = 0;   // ceil(maps / 4) RGBA texel groups
    uint32_t atlases = 0;  // layers of the array (= render targets of a multi pass)
    uint32_t tiles = 0;    // tiles per atlas
    uint32_t cols = 0, rows = 0;
  };
  static Layout layoutFor(uint32_t maps, bool multi, uint32_t size);

  explicit OpacityShadowMaps(const Options& o);
  std::string name() const override { return "osm"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  ShadowLookup lookup() const override;

  const std::vector<float>& slices() const { return slices_; }
  float weight() const { return weight_; }

 private:
  struct MapPass {
    uint32_t targets = 0;
    uint32_t tile = 0;
    bool clear = false;
    Buffer params;
  };
  Pass mapPass(const MapPass& mp) const;

  Options opt_;
  Layout layout_;
  float weight_ = 1.0f;
  std::vector<float> slices_;
  Texture atlases_;                // layout_.atlases layers
  std::vector<Buffer> tileViews_;  // the light's view pointed at each tile
  std::vector<MapPass> passes_;
  std::vector<Pipeline> pipelines_;  // by target count - 1
  Buffer params_;
};

}  // namespace sb
