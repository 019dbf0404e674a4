// `strandbench render`: one scene, one shadow technique, one backend; timed
// over repetitions, with the image and a JSON report.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "harness/image.h"
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

struct RenderRequest {
  std::string scene = "straight";
  std::string shadow = "none";
  std::string oit = "none";  // transparency technique (none | peel | abuffer, ...)
  bool reference = false;    // also render the reference and report errors against it
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
  nlohmann::json report;  // the keys documented for `render --json`
  Image image;            // top row first
  Image reference;        // the reference image (when requested)
};

// Throws InputError (bad scene/technique/options) or DeviceError (backend).
RenderOutcome runRender(const RenderRequest& req);

// Image size, primitive, camera and light (fitted, then overridden) of a request.
RenderSettings makeRenderSettings(const RenderRequest& req, const Scene& scene);
// The device a request names (backend, platform, validation).
std::unique_ptr<Device> makeRequestDevice(const RenderRequest& req);

// "WxH" -> width, height (1..16384 each); throws InputError.
std::pair<uint32_t, uint32_t> parseSize(const std::string& text);
// "x,y,z" -> vec3; throws InputError naming the option.
glm::vec3 parseVec3(const std::string& text, const std::string& option);

}  // namespace sb
