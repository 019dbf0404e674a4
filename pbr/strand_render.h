// The CPU strand references over Embree (docs/physics-reference.md): the transmittance mode
// (the scene's own shading model, each hit's light visibility the exact transmittance
// (1 - shadow_alpha)^n through the strands crossed on the way to the light), the single
// scattering mode (the hair BSDF of hair_bsdf.h lit directly, every fibre a ray crosses, on
// its way to the eye or to a light, attenuating it by fibreTransmittance) and the path traced
// mode (the hair BSDF with multiple scattering). All render progressively, with stratified
// pixel samples and deterministic per-sample seeds, and report each pixel's standard error.
// Plain data in: the harness fills StrandScene from its Scene and settings.
#pragma once

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "pbr/strand_tracer.h"

namespace sb::pbr {

struct TraceLight {
  bool point = false;
  glm::vec3 position{0.0f};    // point light
  glm::vec3 toLight{0, 1, 0};  // directional: unit direction toward the light
  glm::vec3 color{1.0f};       // colour times intensity
  // Transmittance mode: the light's view-projection and depth bias (window depth units),
  // so a strand counts where the rasterized exact shadow counts it: in front of the point by
  // more than the bias, the point inside the light's frustum.
  glm::mat4 viewProj{1.0f};
  float bias = 0.0f;
  // Where not 0, the side of the exact shadow's light map: a shadow ray starts at the centre
  // of the texel the point falls in (at the point's depth), where the raster looks it up.
  uint32_t texels = 0;
  glm::mat4 invViewProj{1.0f};
};

struct StrandScene {
  // Per strand point (the same points as the tracers' geometry).
  std::vector<glm::vec3> colors;       // linear RGB
  std::vector<float> alpha;            // coverage opacity (transmittance mode)
  std::vector<glm::vec3> meshNormals;  // per mesh position; empty: the face normal
  float shadowAlpha = 0.5f;
  glm::vec3 background{0.0f};
  glm::vec3 meshAlbedo{0.75f};
  std::vector<TraceLight> lights;
  // The camera: a pixel's ray goes from eye through invViewProj * (ndc x, ndc y, 1).
  glm::vec3 eye{0, 0, 5};
  glm::mat4 invViewProj{1.0f};
  uint32_t width = 64, height = 64;
};

enum class Mode { Transmittance, Single, Path };

// The fewest samples per pixel whose variance a noise target trusts.
inline constexpr uint32_t kMinSamplesForTarget = 8;

struct RenderOptions {
  Mode mode = Mode::Transmittance;
  uint32_t spp = 1;       // samples per pixel at most (transmittance, 1: the pixel's centre)
  uint32_t bounces = 64;  // path: scattering events at most (Russian roulette ends most first)
  // Stop once the noise (RenderImage::rmsStderr) is below it, after kMinSamplesForTarget
  // samples (0: run all spp).
  float noiseTarget = 0;
  uint64_t seed = 1;
  uint32_t threads = 0;                                            // 0: the hardware's
  float betaM = 0.3f, betaN = 0.3f, alphaDeg = 2.0f, eta = 1.55f;  // the hair BSDF's
  // Single and path modes: the lights' colour is the radiance a Lambertian surface facing them
  // reflects (the raster shading's convention: albedo * colour * cos), so the irradiance is pi
  // times it.
};

// A hit seen by the camera, for the transmittance mode's shading callback.
struct SurfacePoint {
  bool mesh = false;
  glm::vec3 position{0.0f};   // hair: on the strand's axis (where the rasterized ribbon shades)
  glm::vec3 direction{0.0f};  // hair: tangent (root to tip); mesh: normal
  glm::vec3 color{0.0f};      // hair colour
};
// The colour of a point lit by each light with these visibilities (the scene's shading model).
using ShadeFn = std::function<glm::vec3(const SurfacePoint&, const std::vector<float>& visibility)>;

struct RenderImage {
  uint32_t width = 0, height = 0;
  std::vector<glm::vec3> mean;   // per pixel
  std::vector<float> stderror;   // per pixel: the standard error of the mean, RMS over RGB
  uint32_t spp = 0;              // samples per pixel rendered
  bool stoppedAtTarget = false;  // the noise target was reached before spp
  double meanStderr() const;     // over pixels
  double rmsStderr() const;      // sqrt of the mean of stderror^2: the noise's RMSE
};

// progress: after each pass ("pass 3/16, mean stderr 0.012"); it may throw to stop cleanly
// (the harness's throwIfStopped). eye: the tracer for camera rays (and the path's every ray);
// lights: for each light's shadow rays in transmittance mode (one per light, or one for all:
// the eye's, or one with the light's footprint widths).
RenderImage renderStrands(const StrandScene& scene, const StrandTracer& eye,
                          const std::vector<const StrandTracer*>& lights,
                          const RenderOptions& options, const ShadeFn& shade,
                          const std::function<void(const std::string&)>& progress);

// Single mode's light arriving at p from a light at distance dist along wi (unit): the product
// of fibreTransmittance (hair_bsdf.h) over the strands crossed, but skipStrand's (the one p
// lies on; -1: none), at each crossing's h and angle; 0 where the mesh is in the way. Exposed
// for tests.
glm::vec3 lightThroughFibres(const StrandScene& scene, const StrandTracer& tracer,
                             const RenderOptions& options, glm::vec3 p, glm::vec3 wi, float dist,
                             int64_t skipStrand);

// The transmittance toward light l from point p (transmittance mode's rule), exposed for tests.
float lightTransmittance(const StrandScene& scene, const StrandTracer& tracer, std::size_t l,
                         glm::vec3 p);

}  // namespace sb::pbr
