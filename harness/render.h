// `strandbench render`: one scene, one shadow technique, one backend; timed
// over repetitions, with the image and a JSON report.
#pragma once

#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "backends/device.h"
#include "harness/backend_names.h"
#include "imaging/flip.h"
#include "imaging/image.h"
#include "imaging/metrics.h"
#include "render/common/technique.h"
#include "render/common/unit.h"
#include "scenes/scene.h"
#include "scenes/view.h"

namespace sb {

class ReferenceSlice;  // harness/reference_spec.h

// The settings of a request, their CLI flags, suite and manifest keys, ranges and
// defaults are one table: harness/settings.h.

// Every camera and light value can be overridden; unset ones are fitted to the scene.
struct ViewOverrides {
  std::optional<glm::vec3> cameraEye, cameraTarget, cameraUp;
  std::optional<float> fov, nearPlane, farPlane;
  std::optional<std::string> lightType;  // directional | point
  std::optional<glm::vec3> lightPosition, lightDirection, lightColor;
  std::optional<float> lightIntensity;
  bool operator==(const ViewOverrides&) const = default;
};

// Visibility along one light ray (the occupancy paper's Fig. 5): the ray through
// the centre of `texel` of a light map `mapSize` texels wide, sampled at
// `samples` depths from the light's near to far plane.
struct ProbeSpec {
  glm::uvec2 texel{256, 256};
  uint32_t mapSize = 512;
  int samples = 256;
  bool operator==(const ProbeSpec&) const = default;
};

// A light or camera moving over `frames` frames (render --animate): frame t is
// turned by degrees * t / (frames - 1) about the camera's up axis, the light
// about the scene's centre, the camera about its target. Frame 0 is the still
// render.
struct AnimateSpec {
  std::string kind = "light-orbit";  // light-orbit | camera-orbit
  int frames = 8;
  double degrees = 30;
  bool operator==(const AnimateSpec&) const = default;
};

// A light beside the key light (--extra-lights): it gets its own instance of
// the shadow technique, and the image sums every light's shading
// (render/frame/renderer.h). Its frustum is fitted to the scene.
struct ExtraLight {
  std::string type = "directional";  // directional | point
  glm::vec3 at{0, -1, 0};            // point: its position; directional: the direction it travels
  glm::vec3 color{1, 1, 1};
  float intensity = 1.0f;
  bool operator==(const ExtraLight&) const = default;
};

struct RenderRequest {
  std::string scene = "straight";
  // The techniques' specs; by default each family's default (defaultTechnique).
  std::string shadow = defaultTechnique(Family::Shadow).name;
  std::string oit = defaultTechnique(Family::Transparency).name;
  std::string shading = defaultTechnique(Family::Shading).name;
  bool reference = false;  // also render the reference and report errors against it
  // More references beside it (harness/reference_spec.h: a unit's spec), each
  // name once; the error against each is error.<name>. Needs reference.
  std::vector<std::string> references;
  bool image = true;  // false: no final shading; only the visibility error (needs reference)
  std::optional<ProbeSpec> probe;  // also report visibility along a light ray
  bool invariants = false;         // check the outputs and maps (harness/invariants.h)
  bool runToRun = true;            // sweeps with invariants: the case twice, outputs identical
  std::string backend = defaultBackend();
  // Empty: the process's driver (backends/driver_env.h); a request may only name that one.
  std::string driver;
  std::string platform;  // empty: egl for gl, headless for vulkan
  uint32_t width = 512, height = 512;
  std::string primitive = "lines";  // lines | ribbons | world
  std::string geometry = "cpu";     // cpu | compute | mesh (docs/geometry.md)
  float ribbonWidth = 1.0f;
  int msaa = 1;  // samples per pixel of the frame targets: 1, 2, 4, 8 (what the device has)
  int repeat = 1;
  bool timeline = false;  // keep each timed frame's passes with their starts (render --trace)
  int warmup = 1;
  bool validation = false;
  // Refuse the run (InputError) when the resources its timed frames need
  // would take more bytes than this, before they are made; 0: no limit.
  long long memoryLimit = 0;
  ViewOverrides view;
  std::vector<ExtraLight> extraLights;  // lights 2, 3, ... beside the key light of `view`
  // Every frame rendered by the technique and by the reference (needs reference).
  std::optional<AnimateSpec> animate;
  bool operator==(const RenderRequest&) const = default;
};

// One pass's time in each timed frame.
struct PassTimes {
  std::string name;
  Owner owner = Owner::None;  // whose pass (Renderer's PassTime::owner)
  int executions = 0;         // times the pass ran in a frame
  std::vector<double> ms;     // one per timed frame
  PassWork work;              // of the first timed frame (the others are checked equal)
};

struct SceneSummary {
  std::string spec;
  std::size_t strands = 0, points = 0, segments = 0, meshTriangles = 0;
  Bounds bounds;
  std::string up, upReason;  // files: Scene::up, Scene::upReason
  // "strands" (the file's or the generator's) or "fallback" (Strands::thicknessFallback)
  std::string thicknessSource;
  // The groom (scenes/groom.h), when the scene has one: its guides and instances.
  std::size_t guides = 0, instances = 0;
};

// A measure's result (harness/measures/measure_unit.h): what one measure unit found, kept
// beside the core fields, and its keys in the report.
class MeasureSlice {
 public:
  virtual ~MeasureSlice() = default;
  // Adds its top-level keys to the `render --json` object.
  virtual void json(nlohmann::json& /*report*/) const {}
  // Adds its keys to the report's `error` object (written with a reference).
  virtual void errorJson(nlohmann::json& /*error*/) const {}
};

// What runRender measured; renderJson writes it as the `render --json` object
// (the sweep's case files add their own keys to that).
struct RenderResult {
  DeviceInfo device;
  SceneSummary scene;
  std::string shadow, oit;  // the technique specs as run
  std::string shading;      // the hair shading model spec
  std::string primitive;
  std::string geometry;
  uint32_t width = 0, height = 0;
  int repeat = 0, warmup = 0;
  std::vector<std::string> graph;  // the passes of a timed frame
  // What building the frame ran: the pipelines compiled (name, technique) and
  // the techniques' preparations; a technique whose passes the graph culled
  // has neither (Renderer::compiledPipelines).
  std::vector<std::pair<std::string, std::string>> pipelines;
  std::vector<std::string> preparations;
  // The passes of the untimed frame that measured errors and the probe (when one ran).
  std::optional<std::vector<std::string>> measurementGraph;
  std::vector<PassTimes> passes;  // in the order they first ran
  // Passes whose work counters differed between timed frames (a warning: the
  // counters are exact, so the same frame should repeat them).
  std::vector<std::string> workVaries;
  std::vector<double> frameMs;  // per timed frame: the sum of its passes
  // With RenderRequest::timeline: per timed frame, each pass execution with its start.
  std::vector<std::vector<PassTiming>> timeline;
  // This run's own resources (not the reference's), sorted by name.
  std::vector<ResourceBytes> resources;
  // Their bytes as known before the first frame (from the culled graph).
  std::size_t estimatedBytes = 0;
  // The reference's shadow and transparency specs (with a reference or a probe).
  std::optional<std::pair<std::string, std::string>> reference;
  std::optional<ImageError> imageError;  // with a reference and an image
  std::optional<FlipResult> flip;  // LDR-FLIP of the image against the reference, 67 ppd (same)
  std::optional<VisibilityError> visibilityError;  // with a reference
  // The error against each further reference (RenderRequest::references), in
  // their order: error.<name> in JSON, the same fields as error.image.
  struct MoreReference {
    std::string name, spec;          // the unit's name and canonical spec
    int samples = 1;                 // per pixel (along each axis where the unit says so)
    uint32_t width = 0, height = 0;  // the samples rendered (image size times samples)
    uint32_t lightSize = 0;          // its exact shadow's light map (size times samples)
    double frameMs = 0;              // its frame's passes
    double wallMs = 0;          // all of it: device, counting, pipelines, frame, read back, filter
    std::size_t bytes = 0;      // its resources (on a device of its own)
    std::size_t hostBytes = 0;  // the host memory of its read back and filter
    bool cached = false;        // taken from the sweep's cache (the cost is the first render's)
    std::vector<std::string> warnings;  // its techniques' (a fragment list overflow)
    ImageError image;                   // of the image against it
    FlipResult flip;
    // Means over pixels and RGB of the image and of the reference (how much brighter or
    // darker one is, the part of the error a scale would explain; written by a slice: pbr's).
    double imageMean = 0, referenceMean = 0;
    // The exposure scale s that brings the image nearest the reference (least squares over
    // pixels and RGB: sum(image reference) / sum(image^2)), and the RMSE of s * image.
    double bestScale = 1, scaledRmse = 0;
    Image referenceImage;  // the filtered reference, the image's size
    // The reference's own part (pbr's noise, cache, ...), written by it into error.<name>
    // (harness/reference_spec.h); null where it has none.
    std::shared_ptr<const ReferenceSlice> slice;
  };
  std::vector<MoreReference> moreReferences;
  std::optional<DepthComplexity> eyeComplexity, lightComplexity;
  std::vector<std::string> warnings;              // the input's, the techniques', the reference's
  std::optional<std::size_t> validationMessages;  // with validation
  // The shadow technique's counters, then the transparency technique's (after
  // the frames), and, when the timing is an emulation, why
  // (OitTechnique::timingEmulated).
  std::vector<Counter> counters;
  std::string timingEmulated;
  // The tier the techniques ran (ShadowTechnique::tier, OitTechnique::tier):
  // "software" or "ray_query"; both named when they differ; empty without tiers.
  // tierReason: why (tier=auto's rule for the device, or the tier asked for), each
  // technique's named when they differ.
  std::string tier, tierReason;

  // A window platform: each timed frame was shown in the window (Device::present).
  struct Presented {
    int frames = 0;          // timed frames presented
    std::string how;         // DeviceInfo::present
    std::vector<double> ms;  // per timed frame: the present alone
    // The image once more presented after the timed frames (untimed), read
    // back from the window's framebuffer or swapchain image; top row first,
    // RGBA with alpha 1 (the window has none). Empty if the window was minimized.
    Image image;
  };
  std::optional<Presented> presented;

  Image image;                      // top row first (empty without an image)
  Image referenceImage;             // with a reference and an image
  std::vector<uint8_t> visibility;  // R32F visibility image (with a reference)

  // What the measure units found (harness/measures/), in the order they ran.
  std::vector<std::shared_ptr<const MeasureSlice>> measured;
  // A measure's slice by its type (harness/measures/<name>/<name>.h); null where it has none.
  template <class T>
  const T* measure() const {
    for (const auto& m : measured)
      if (const T* t = dynamic_cast<const T*>(m.get())) return t;
    return nullptr;
  }
  // Puts `slice` in place of the one of its type, or after the others.
  template <class T>
  void setMeasure(std::shared_ptr<const T> slice) {
    for (auto& m : measured)
      if (dynamic_cast<const T*>(m.get())) {
        m = std::move(slice);
        return;
      }
    measured.push_back(std::move(slice));
  }

  // Bytes of this run's resources whose owner is `owner` (shadow, oit, scene, frame).
  std::size_t bytesOwnedBy(Owner owner) const;
};

// The `render --json` object (keys in docs/suites-and-results.md).
nlohmann::json renderJson(const RenderResult& r);
// A pass's (or a frame's) work counters as JSON; the API's counts are null
// where the device has no queries; `resources`: with each resource touched.
nlohmann::json workJson(const PassWork& w, bool resources);
// The timed frames as a Chrome/Perfetto trace (trace-event JSON, "X" slices in
// microseconds): one slice per frame, its passes nested in it, the frames one after
// another on one track; args name the clock and each pass's execution. Needs timeline.
nlohmann::json traceJson(const RenderResult& r);

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
  // Images of own-error references (exact in one family only), by key.
  std::map<std::string, Image> ownReferences;
  std::map<std::string, std::shared_ptr<const Scene>> scenes;
  std::map<std::string, Reference> references;
  // Further references (RenderRequest::references) by referenceKey and spec:
  // the image and the cost, without the errors.
  std::map<std::string, RenderResult::MoreReference> moreReferences;
  int referenceRenders = 0;  // how many references were rendered (not taken from the cache)
};

// Throws InputError (bad scene/technique/options) or DeviceError (backend).
// With a cache, scenes and references are taken from it or added to it.
// With `device` (of the request's backend), it renders there instead of on a
// device of its own, and leaves showing the image to the caller (`view`):
// only a device of its own on a window platform presents each timed frame.
RenderResult runRender(const RenderRequest& req, RenderCache* cache = nullptr,
                       Device* device = nullptr);

// World points along the probe ray and their light depths in [0, 1].
std::vector<glm::vec3> probeRay(const Light& light, const ProbeSpec& probe,
                                std::vector<float>& depths);

// Image size, primitive, camera and light (fitted, then overridden) of a request.
RenderSettings makeRenderSettings(const RenderRequest& req, const Scene& scene);
// The device a request names (backend, platform, validation).
std::unique_ptr<Device> makeRequestDevice(const RenderRequest& req);

}  // namespace sb
