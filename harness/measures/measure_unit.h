// What a render measures beyond its core (frames, passes, memory, the image and its error
// against the references): each measure is a unit, a folder harness/measures/<name>/ whose
// unit.cpp registers it (SB_MEASURE, below) with its name, help and how it measures, as
// references and techniques register themselves. Nothing central lists them: runRender runs
// every registered measure after the reference (harness/render.cpp, step 6), keeps the
// slices they return in RenderResult::measured, and renderJson asks each slice to write its
// own keys of the report. A caller reads one with RenderResult::measure<T>().
#pragma once

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/unit_registry.h"
#include "harness/render.h"

namespace sb {

class Renderer;

// What a measure reads: the request, the scenes, the settings and specs as run, the
// renderer after its frames (and the measurement frame), the device, the sweep's cache, the
// exact reference where the run made one, and the core result with the slices of the
// measures before it.
struct MeasureInputs {
  const RenderRequest& req;
  const Scene& scene;  // as drawn (with its level of detail)
  const Scene& full;   // the full model (the same scene without a level of detail)
  const RenderSettings& settings;
  const Spec &shadow, &oit, &refShadow;
  const std::vector<float>& probeDepths;  // the probe ray's light depths (with a probe)
  Renderer& renderer;
  Device& dev;
  RenderCache* cache;
  const RenderCache::Reference* reference;  // the exact reference; null without one
  // The full model's exact reference (cached per sweep); only with a level of detail.
  std::function<const RenderCache::Reference*()> fullModelReference;
  const RenderResult& out;
};

struct MeasureDescriptor {
  std::string name;  // its key in the report
  std::string help;
  // Measures run by increasing order, then by name; one that reads another's slice comes
  // after it (invariants, which check every error reported, run last).
  int order = 0;
  // Its slice, or null where the request does not ask for it.
  std::function<std::shared_ptr<const MeasureSlice>(const MeasureInputs&)> measure;
  std::string folder;  // harness/measures/<folder>/, filled by the registrar
};

struct MeasureRegistrar {
  MeasureRegistrar(const char* file, MeasureDescriptor d);
};

// A measure's folder registers it from its unit.cpp, at file scope:
//   SB_MEASURE({.name = "probe", .help = "...", .measure = ...});
#define SB_MEASURE(...) SB_REGISTER(MeasureRegistrar, __VA_ARGS__)

// Every measure, in the order they run.
std::vector<const MeasureDescriptor*> measureCatalog();

// Shared by the measures' reports (harness/render_json.cpp): samples as {median, min, max,
// mean, stddev, samples}, a visibility error as {rmse, max, pixels}; and R32F visibility
// bytes as floats.
nlohmann::json statsJson(const std::vector<double>& samples);
nlohmann::json visibilityJson(const VisibilityError& e);
std::vector<float> visibilityFloats(const std::vector<uint8_t>& bytes);

}  // namespace sb
