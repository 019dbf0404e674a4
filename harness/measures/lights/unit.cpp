// The lights measure: each light's share of a run with extra lights (lights.h).
#include "harness/measures/lights/lights.h"
#include "harness/measures/measure_unit.h"
#include "render/frame/renderer.h"

namespace sb {
namespace {

// Which light a pass or resource is (Renderer::lightPrefix): an extra light's
// index, else 0 (the key light); -1 for the sum of the lights.
int lightOfName(const std::string& name, std::size_t lights) {
  if (name == "lights.sum") return -1;
  for (std::size_t i = 1; i < lights; ++i)
    if (name.rfind(Renderer::lightPrefix(i), 0) == 0) return static_cast<int>(i);
  return 0;
}

std::shared_ptr<const MeasureSlice> measure(const MeasureInputs& in) {
  const RenderSettings& s = in.settings;
  const RenderResult& r = in.out;
  if (s.extraLights.empty()) return nullptr;
  auto out = std::make_shared<LightShares>();
  std::vector<LightShare>& shares = out->lights;
  shares.resize(1 + s.extraLights.size());
  for (std::size_t i = 0; i < shares.size(); ++i) {
    shares[i].light = i == 0 ? s.light : s.extraLights[i - 1];
    shares[i].ms.assign(r.frameMs.size(), 0.0);
  }
  for (const PassTimes& p : r.passes) {
    const int i = lightOfName(p.name, shares.size());
    if (i < 0) continue;
    for (std::size_t f = 0; f < p.ms.size() && f < shares[i].ms.size(); ++f)
      shares[i].ms[f] += p.ms[f];
  }
  for (const ResourceBytes& res : r.resources) {
    const int i = lightOfName(res.name, shares.size());
    if (i < 0 || (i == 0 && res.owner == Owner::Scene)) continue;
    shares[i].bytes += res.bytes;
    if (res.owner == Owner::Shadow) shares[i].shadowBytes += res.bytes;
  }
  return out;
}

}  // namespace

void LightShares::json(nlohmann::json& report) const {
  auto v3 = [](const glm::vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const Light& l = lights[i].light;
    const bool point = l.type == LightType::Point;
    list.push_back({{"light", i + 1},
                    {"type", point ? "point" : "directional"},
                    {point ? "position" : "direction", v3(point ? l.position : l.direction)},
                    {"color", v3(l.color)},
                    {"intensity", l.intensity},
                    {"prefix", Renderer::lightPrefix(i)},
                    {"ms", statsJson(lights[i].ms)},
                    {"shadow_bytes", lights[i].shadowBytes},
                    {"bytes", lights[i].bytes}});
  }
  report["lights"] = list;
}

}  // namespace sb

SB_MEASURE({.name = "lights",
            .help = "with extra lights: each light's share of the timed frames and of the "
                    "memory, told apart by the names of passes and resources",
            .measure = sb::measure});
