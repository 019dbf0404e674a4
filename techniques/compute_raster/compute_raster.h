// A compute strand rasterizer, as engines shipping strand hair now draw it
// (Frostbite's "Every Strand Counts", Unity's Enemies hair, Unreal's
// HairStrands compute raster): no hardware rasterization of the hair at all.
//  1. shade (shading=point): each segment's two ends shaded once, through the
//     shading model and the shadow technique's lookup;
//  2. raster: one invocation per segment projects it and walks its pixels,
//     giving each an analytic coverage from the strand's width (or a binary
//     one, as the hardware draws the same strands), and appends the fragments
//     in front of the opaque depth to their screen tile's list;
//  3. bucket: one workgroup per tile buckets the tile's list by pixel (a
//     counting sort in shared memory, into a second pool as large as the
//     first) and writes each pixel's range;
//  4. resolve: each pixel takes its fragments front to back by (depth,
//     segment), each time the nearest after the last, compositing them until
//     what is left to see is under the termination threshold (early
//     termination: the deeper fragments are never ordered).
// The lists live in one pool: with fragments=0 each tile gets exactly what a
// counting pass found in prepare(); with fragments=N each tile gets N entries
// (the engines' fixed layout, tiles x N x 16 bytes), twice (the buckets). A
// full list drops fragments, counted ("dropped_fragments", "overflowed_tiles")
// and warned about, never silently. Level of detail is the scene's (lod=,
// lod_pixels=; docs/geometry.md), one mechanism for every technique and path:
// this draws the strands it kept, and width_from=thickness their widened widths.
#pragma once

#include "render/common/hair_oit.h"

namespace sb {

class OptionReader;
class HairShading;

class ComputeRasterOit : public CompositedOit {
 public:
  struct Options {
    uint32_t tile = 8;              // pixels per tile side (8 or 16)
    uint32_t fragments = 0;         // entries per tile; 0: as counted in prepare()
    bool analytic = true;           // coverage=analytic (else binary)
    bool perPoint = true;           // shading=point (else fragment)
    float width = 0;                // strand width in pixels; 0: the frame's (lines 1, ribbons)
    bool thickness = false;         // width_from=thickness: the scene's thickness, projected
    float terminate = 1.0f / 1024;  // early-termination transmittance
  };
  explicit ComputeRasterOit(Options o) : o_(o) {}
  std::string name() const override { return "compute_raster"; }
  void setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
             const HairShading& shading, const OitTargets& targets) override;
  bool needsPrepare() const override { return o_.fragments == 0; }
  void prepare(Device& dev) override;
  void addPasses(FrameGraph& graph, Device& dev) override;
  std::vector<std::string> warnings(Device& dev) override;
  std::vector<Counter> counters(Device& dev) override;

 private:
  Pass shadePass() const;
  Pass countPass() const;  // prepare()'s: the raster pass counting only
  Pass rasterPass() const;
  Pass bucketPass() const;
  Pass resolvePass() const;
  std::vector<uint32_t> status(Device& dev);
  uint32_t tiles() const { return tilesX_ * tilesY_; }

  Options o_;
  uint32_t tilesX_ = 0, tilesY_ = 0;
  uint64_t pool_ = 0;
  Buffer params_, cursor_, layout_, fragments_, buckets_, ranges_, shaded_;
  Pipeline count_, shade_, raster_, bucket_, resolve_;
};

}  // namespace sb
