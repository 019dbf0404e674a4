// The render result as JSON (`render --json`, a sweep's results.json).
#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "harness/measures/measure_unit.h"
#include "harness/reference_spec.h"
#include "harness/render_steps.h"
#include "render/frame/renderer.h"
#include "reports/stats.h"

namespace sb {
namespace {

nlohmann::json boundsJson(const Bounds& b) {
  return {{"min", {b.min.x, b.min.y, b.min.z}}, {"max", {b.max.x, b.max.y, b.max.z}}};
}

}  // namespace

nlohmann::json visibilityJson(const VisibilityError& e) {
  return {{"rmse", e.rmse}, {"max", e.max}, {"pixels", e.pixels}};
}

nlohmann::json statsJson(const std::vector<double>& samples) {
  const Stats s = summarize(samples);
  return {{"median", s.median}, {"min", s.min},       {"max", s.max},
          {"mean", s.mean},     {"stddev", s.stddev}, {"samples", samples}};
}

// `error` of the report: image (with an image) and visibility, the total error (against exact
// shadows plus exact transparency, written once: there is no separate `total` copy), each
// further reference's, and each measure's (own, by_eye_layers, full_model).
nlohmann::json errorJson(const RenderResult& r) {
  nlohmann::json error;
  if (r.imageError) error["image"] = toJson(*r.imageError);
  if (r.flip) error["image"]["flip"] = toJson(*r.flip);
  if (r.visibilityError) error["visibility"] = visibilityJson(*r.visibilityError);
  // Each further reference under its name, with error.image's fields and its cost.
  for (const RenderResult::MoreReference& m : r.moreReferences) {
    nlohmann::json e = toJson(m.image);
    e["flip"] = toJson(m.flip);
    e["reference"] = {{"spec", m.spec},
                      {"samples", m.samples},
                      {"size", {m.width, m.height}},
                      {"light_map_size", m.lightSize},
                      {"frame_ms", m.frameMs},
                      {"wall_ms", m.wallMs},
                      {"bytes", m.bytes},
                      {"host_bytes", m.hostBytes},
                      {"cached", m.cached}};
    if (m.slice) m.slice->json(m, e);  // the reference's own fields
    error[m.name] = e;
  }
  for (const auto& m : r.measured) m->errorJson(error);
  return error;
}

namespace {

nlohmann::json complexityJson(const std::optional<DepthComplexity>& c) {
  if (!c) return nullptr;
  return {{"max", c->max}, {"mean", c->mean}, {"fragments", c->total}};
}

}  // namespace

nlohmann::json renderJson(const RenderResult& r) {
  nlohmann::json j;
  j["backend"] = r.device.backend;
  j["platform"] = r.device.platform;
  j["device"] = r.device.device;
  j["driver"] = r.device.driver;
  j["driver_name"] = r.device.driverName;
  j["timing"] = r.device.timing;
  j["lines"] = r.device.lines;
  j["scene"] = {{"spec", r.scene.spec},
                {"strands", r.scene.strands},
                {"points", r.scene.points},
                {"segments", r.scene.segments},
                {"mesh_triangles", r.scene.meshTriangles},
                {"bounds", boundsJson(r.scene.bounds)},
                {"thickness_source", r.scene.thicknessSource}};
  if (r.scene.instances > 0) {
    j["scene"]["guides"] = r.scene.guides;
    j["scene"]["instances"] = r.scene.instances;
  }
  if (!r.scene.up.empty()) {
    j["scene"]["up"] = r.scene.up;
    j["scene"]["up_reason"] = r.scene.upReason;
  }
  j["shadow"] = r.shadow;
  j["oit"] = r.oit;
  j["shading"] = r.shading;
  j["primitive"] = r.primitive;
  j["geometry"] = r.geometry;
  j["size"] = {r.width, r.height};
  j["repeat"] = r.repeat;
  j["warmup"] = r.warmup;
  j["graph"] = r.graph;
  nlohmann::json pipelines = nlohmann::json::array();
  for (const auto& [name, technique] : r.pipelines)
    pipelines.push_back({{"name", name}, {"technique", technique}});
  j["build"] = {{"pipelines", pipelines}, {"preparations", r.preparations}};
  j["passes"] = nlohmann::json::array();
  PassWork frame;
  for (const PassTimes& p : r.passes) {
    j["passes"].push_back({{"name", p.name},
                           {"executions", p.executions},
                           {"ms", statsJson(p.ms)},
                           {"work", workJson(p.work, true)}});
    frame += p.work;
  }
  j["frame_ms"] = statsJson(r.frameMs);
  j["frame_work"] = workJson(frame, false);
  j["counters_from"] = r.device.counters;

  nlohmann::json resources = nlohmann::json::array();
  std::size_t total = 0;
  for (const auto& res : r.resources) {
    resources.push_back(
        {{"name", res.name}, {"owner", ownerName(res.owner)}, {"bytes", res.bytes}});
    total += res.bytes;
  }
  j["memory"] = {{"shadow_bytes", r.bytesOwnedBy(Owner::Shadow)},
                 {"oit_bytes", r.bytesOwnedBy(Owner::Oit)},
                 {"scene_bytes", r.bytesOwnedBy(Owner::Scene)},
                 {"frame_bytes", r.bytesOwnedBy(Owner::Frame)},
                 {"total_bytes", total},
                 {"estimated_bytes", r.estimatedBytes},
                 {"resources", resources}};

  if (r.measurementGraph) j["measurement_graph"] = *r.measurementGraph;
  if (r.reference) j["reference"] = {{"shadow", r.reference->first}, {"oit", r.reference->second}};
  if (r.visibilityError) j["error"] = errorJson(r);
  for (const auto& m : r.measured) m->json(j);
  if (r.eyeComplexity || r.lightComplexity)
    j["depth_complexity"] = {{"eye", complexityJson(r.eyeComplexity)},
                             {"light", complexityJson(r.lightComplexity)}};
  j["warnings"] = r.warnings;
  if (!r.counters.empty()) {
    nlohmann::json counters = nlohmann::json::object();
    for (const Counter& c : r.counters) counters[c.name] = c.value;
    j["counters"] = counters;
  }
  if (!r.timingEmulated.empty()) j["timing_emulated"] = r.timingEmulated;
  if (!r.tier.empty()) j["tier"] = r.tier;
  if (!r.tierReason.empty()) j["tier_reason"] = r.tierReason;
  if (r.validationMessages) j["validation_messages"] = *r.validationMessages;
  if (r.presented) {
    // frame_ms plus the present: the frame time with presentation included.
    std::vector<double> withPresent = r.frameMs;
    for (std::size_t i = 0; i < withPresent.size() && i < r.presented->ms.size(); ++i)
      withPresent[i] += r.presented->ms[i];
    j["presented"] = {{"frames", r.presented->frames},
                      {"how", r.presented->how},
                      {"present_ms", statsJson(r.presented->ms)},
                      {"frame_ms", statsJson(withPresent)}};
  }
  return j;
}

nlohmann::json workJson(const PassWork& w, bool resources) {
  auto api = [&](uint64_t v) { return w.statistics ? nlohmann::json(v) : nlohmann::json(); };
  nlohmann::json j = {{"vertices", api(w.vertices)},
                      {"primitives", api(w.primitives)},
                      {"vertex_invocations", api(w.vertexInvocations)},
                      {"clip_invocations", api(w.clipInvocations)},
                      {"clip_primitives", api(w.clipPrimitives)},
                      {"fragment_invocations", api(w.fragmentInvocations)},
                      {"compute_invocations", api(w.computeInvocations)},
                      {"samples_passed", api(w.samplesPassed)},
                      {"draws", w.draws},
                      {"dispatches", w.dispatches},
                      {"bytes_written", w.bytesWritten},
                      {"bytes_read", w.bytesRead},
                      {"bytes_storage", w.bytesStorage}};
  if (resources) {
    nlohmann::json list = nlohmann::json::array();
    for (const PassResource& x : w.resources) {
      nlohmann::json e = {
          {"name", x.name}, {"access", x.access}, {"format", x.format}, {"bytes", x.bytes}};
      if (x.format != "buffer") e["extent"] = {x.width, x.height, x.layers, x.samples};
      list.push_back(e);
    }
    j["resources"] = list;
  }
  return j;
}

nlohmann::json traceJson(const RenderResult& r) {
  nlohmann::json events = nlohmann::json::array();
  const std::string thread = r.device.backend + " " + r.device.device;
  events.push_back({{"name", "process_name"},
                    {"ph", "M"},
                    {"pid", 1},
                    {"args", {{"name", "strandbench render"}}}});
  events.push_back(
      {{"name", "thread_name"}, {"ph", "M"}, {"pid", 1}, {"tid", 1}, {"args", {{"name", thread}}}});
  double at = 0.0;  // microseconds: frames one after another, 10 us apart
  for (std::size_t f = 0; f < r.timeline.size(); ++f) {
    const std::vector<PassTiming>& passes = r.timeline[f];
    double end = 0.0, sum = 0.0;  // milliseconds from the frame's start
    for (const PassTiming& p : passes) {
      end = std::max(end, p.startMs + p.ms);
      sum += p.ms;
    }
    events.push_back({{"name", "frame " + std::to_string(f + 1)},
                      {"cat", "frame"},
                      {"ph", "X"},
                      {"pid", 1},
                      {"tid", 1},
                      {"ts", at},
                      {"dur", end * 1000.0},
                      {"args", {{"passes", passes.size()}, {"pass_ms_sum", sum}}}});
    std::map<std::string, int> executions;
    for (const PassTiming& p : passes)
      events.push_back(
          {{"name", p.name},
           {"cat", "pass"},
           {"ph", "X"},
           {"pid", 1},
           {"tid", 1},
           {"ts", at + p.startMs * 1000.0},
           {"dur", p.ms * 1000.0},
           {"args", {{"execution", ++executions[p.name]}, {"work", workJson(p.work, false)}}}});
    at += end * 1000.0 + 10.0;
  }
  return {{"traceEvents", events},
          {"displayTimeUnit", "ms"},
          {"otherData",
           {{"scene", r.scene.spec},
            {"shadow", r.shadow},
            {"oit", r.oit},
            {"backend", r.device.backend},
            {"device", r.device.device},
            {"clock", r.device.timing}}}};
}

}  // namespace sb
