// `--reference pbr:...`: the CPU strand references of pbr/ (transmittance or path traced) for
// a render, made from its Scene and settings, cached on disk by a hash of everything they
// depend on (docs/physics-reference.md "Cache"). Its unit (unit.cpp) declares the options;
// this is what it renders and writes (error.pbr's noise, scaled, mean and reference.pbr).
#pragma once

#include <string>

#include "harness/reference_spec.h"
#include "harness/render.h"
#include "pbr/strand_render.h"

namespace sb {

// A spec of the reference: the mode (transmittance, single, path), samples per pixel, the
// path's scattering events at most, the strands' width model (auto: footprint in
// transmittance mode, world otherwise), the world width of strands without one (0: one pixel
// at the scene's centre), the noise target (RMS standard error; 0: all spp) and the seed.
struct PbrReference : Reference {
  std::string mode = "path";
  int spp = 16, bounces = 64;
  std::string width = "auto";
  double thickness = 0, noise = 0;
  int seed = 1;
  // "pbr:mode=path,spp=16,bounces=64,..." (every option: the disk cache's key reads it).
  std::string str() const override;
  RenderResult::MoreReference render(const ReferenceInputs& in) const override;
};

// What it rendered, its noise and its disk cache: its slice of the result.
struct PbrSlice : ReferenceSlice {
  std::string mode, width;      // width: footprint or world (auto resolved)
  double rasterAmbient = 0;     // the raster's ambient term in this render (the tracer: none)
  std::string shadowRays;       // how a strand between a point and a light counts
  double thickness = 0;         // world: the strands' mean width
  std::string thicknessSource;  // world: "strands" (the file's or scene's) or "fallback"
  uint32_t spp = 0;             // samples per pixel rendered
  bool stoppedAtTarget = false;
  double meanStderr = 0, noiseRmse = 0;  // per pixel; noiseRmse: sqrt(mean stderr^2)
  std::string key, file;                 // the cache's hash (hex) and file
  bool cacheHit = false;
  double renderMs = 0;  // the render that made it (also on a cache hit: the first's)
  void json(const RenderResult::MoreReference& m, nlohmann::json& e) const override;
};

// A parsed spec's options (InputError when it is not a pbr spec), and a result's slice (null
// when the result is not pbr's): for tests.
const PbrReference& pbrOptions(const ReferenceSpec& spec);
const PbrSlice* pbrSlice(const RenderResult::MoreReference& m);

// The folder of the cache: $SB_PBR_CACHE, else $XDG_CACHE_HOME/strandbench/pbr, else
// $HOME/.cache/strandbench/pbr; "" when SB_PBR_CACHE is "off" (no cache).
std::string pbrCacheDir();

// The scene, lights and camera as pbr's plain data, and the tracers' geometry with the widths
// of `spec` (exposed for tests).
// footprint: shadow rays start at the centres of the exact shadow's texels.
pbr::StrandScene pbrScene(const Scene& scene, const RenderSettings& settings, const Spec& refShadow,
                          bool footprint);
// The per-point radius: the footprint of eye pixels (light < 0) or of light l's texels, or
// the world width.
pbr::TraceGeometry pbrGeometry(const Scene& scene, const RenderSettings& settings,
                               const Spec& refShadow, const PbrReference& spec, int light = -1);
// The world width model's resolved thickness (spec.thickness, or one pixel at the centre).
double pbrThickness(const Scene& scene, const RenderSettings& settings, const PbrReference& spec);
// auto resolved: footprint (transmittance) or world (path).
std::string pbrWidthModel(const PbrReference& spec);

}  // namespace sb
