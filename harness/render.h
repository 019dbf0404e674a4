// `strandbench render`: one scene, one shadow technique, one backend; timed
// over repetitions, with the image and a JSON report.
#pragma once

#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "harness/image.h"
#include "scenes/scene.h"
#include "scenes/view.h"
#include "techniques/common/technique.h"

namespace sb {

// Every camera and light value can be overridden; unset ones are fitted to the scene.
struct ViewOverrides {
  std::optional<glm::vec3> cameraEye, cameraTarget, cameraUp;
  std::optional<float> fov, nearPlane, farPlane;
  std::optional<std::string> lightType;  // directional | point
  std::optional<glm::vec3> lightPosition, lightDirection, lightColor;
  std::optional<float> lightIntensity;
};

// Visibility along one light ray (the occupancy paper's Fig. 5): the ray through
// the centre of `texel` of a light map `mapSize` texels wide, sampled at
// `samples` depths from the light's near to far plane.
struct ProbeSpec {
  glm::uvec2 texel{256, 256};
  uint32_t mapSize = 512;
  int samples = 256;
};

struct RenderRequest {
  std::string scene = "straight";
  std::string shadow = "none";
  std::string oit = "none";  // transparency technique (none | peel | abuffer, ...)
  bool reference = false;    // also render the reference and report errors against it
  bool image = true;         // false: no final shading; only the visibility error (needs reference)
  std::optional<ProbeSpec> probe;  // also report visibility along a light ray
  bool invariants = false;         // check the outputs and maps (harness/invariants.h)
  std::string backend = "gl";
  std::string platform;  // empty: egl for gl, headless for vulkan
  uint32_t width = 512, height = 512;
  std::string primitive = "lines";  // lines | ribbons
  float ribbonWidth = 1.0f;
  int repeat = 1;
  int warmup = 1;
  bool validation = false;
  ViewOverrides view;
};

struct RenderOutcome {
  nlohmann::json report;            // the keys documented for `render --json`
  Image image;                      // top row first
  Image reference;                  // the reference image (when requested)
  std::vector<uint8_t> visibility;  // R32F visibility image (with a reference)
  std::vector<float> probe;         // visibility along the probe ray (with a probe)
};

// What a sweep computes once and reuses across its cases: scenes by spec and
// references by backend, scene, view, reference technique and probe.
struct RenderCache {
  struct Reference {
    Image image;                      // empty when made for a visibility-only run
    std::vector<uint8_t> visibility;  // R32F per pixel
    std::vector<float> probe;         // exact visibility along the probe ray
    std::optional<DepthComplexity> eye, light;
    std::vector<std::string> warnings;
  };
  std::map<std::string, std::shared_ptr<const Scene>> scenes;
  std::map<std::string, Reference> references;
  int referenceRenders = 0;  // how many references were rendered (not taken from the cache)
};

// Throws InputError (bad scene/technique/options) or DeviceError (backend).
// With a cache, scenes and references are taken from it or added to it.
RenderOutcome runRender(const RenderRequest& req, RenderCache* cache = nullptr);

// World points along the probe ray and their light depths in [0, 1].
std::vector<glm::vec3> probeRay(const Light& light, const ProbeSpec& probe,
                                std::vector<float>& depths);

// Image size, primitive, camera and light (fitted, then overridden) of a request.
RenderSettings makeRenderSettings(const RenderRequest& req, const Scene& scene);
// The device a request names (backend, platform, validation).
std::unique_ptr<Device> makeRequestDevice(const RenderRequest& req);

// "WxH" -> width, height (1..16384 each); throws InputError.
std::pair<uint32_t, uint32_t> parseSize(const std::string& text);
// "x,y,z" -> vec3; throws InputError naming the option.
glm::vec3 parseVec3(const std::string& text, const std::string& option);

}  // namespace sb
