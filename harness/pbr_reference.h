// `--reference pbr:...`: the CPU strand references of pbr/ (transmittance or path traced) for
// a render, made from its Scene and settings, cached on disk by a hash of everything they
// depend on (docs/physics-reference.md "Cache"). Internal to harness/render*.cpp and tests.
#pragma once

#include <string>

#include "harness/reference_spec.h"
#include "harness/render.h"
#include "pbr/strand_render.h"

namespace sb {

// The folder of the cache: $SB_PBR_CACHE, else $XDG_CACHE_HOME/strandbench/pbr, else
// $HOME/.cache/strandbench/pbr; "" when SB_PBR_CACHE is "off" (no cache).
std::string pbrCacheDir();

// The pbr reference of `spec` for this scene and settings (refShadow: the exact shadow whose
// light map size and bias the footprint widths and the transmittance rule take).
RenderResult::MoreReference renderPbrReference(const Scene& scene, const RenderSettings& settings,
                                               const Spec& refShadow, const ReferenceSpec& spec);

// The scene, lights and camera as pbr's plain data, and the tracers' geometry with the widths
// of `spec` (exposed for tests).
pbr::StrandScene pbrScene(const Scene& scene, const RenderSettings& settings,
                          const Spec& refShadow);
// The per-point radius: the footprint of eye pixels (light < 0) or of light l's texels, or
// the world width.
pbr::TraceGeometry pbrGeometry(const Scene& scene, const RenderSettings& settings,
                               const Spec& refShadow, const ReferenceSpec& spec, int light = -1);
// The world width model's resolved thickness (spec.thickness, or one pixel at the centre).
double pbrThickness(const Scene& scene, const RenderSettings& settings, const ReferenceSpec& spec);
// auto resolved: footprint (transmittance) or world (path).
std::string pbrWidthModel(const ReferenceSpec& spec);

}  // namespace sb
