// `strandbench probe`: the exact visibility along one light ray and each shadow
// technique's reconstruction of it, as CSV (the occupancy paper's Fig. 5).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "cli/commands.h"
#include "harness/render.h"
#include "render/frame/renderer.h"
#include "reports/files.h"

namespace sb {

namespace {

struct ProbeRequest {
  RenderRequest render;
  std::vector<std::string> shadows;  // none: the exact curve alone
  std::string texel = "256,256";
  int mapSize = 512;  // signed, so that a negative size gets the range message
  int samples = 256;
  std::string out;
};

int runProbe(const ProbeRequest& p) {
  if (p.out.empty()) throw InputError("--out FILE.csv is required");
  checkOutputPath("--out", p.out, {".csv"});
  if (p.samples < 2 || p.samples > 1000000) throw InputError("--samples must be in 2..1000000");
  if (p.mapSize < 1 || p.mapSize > 16384)
    throw InputError("--map-size " + std::to_string(p.mapSize) + ": must be in 1..16384");
  const uint32_t mapSize = static_cast<uint32_t>(p.mapSize);
  unsigned x = 0, y = 0;
  char comma = 0;
  std::istringstream in(p.texel);
  if (!(in >> x >> comma >> y) || comma != ',' || !in.eof() || x >= mapSize || y >= mapSize)
    throw InputError("--texel " + p.texel + ": expected X,Y inside the " + std::to_string(mapSize) +
                     "x" + std::to_string(mapSize) + " map");

  RenderCache cache;  // the scene, built once
  checkRenderRequest(p.render, false, &cache);
  const Scene& scene = *cache.scenes.at(p.render.scene);
  RenderSettings settings = makeRenderSettings(p.render, scene);
  std::vector<float> depths;
  settings.probePoints = probeRay(settings.light, {{x, y}, mapSize, p.samples}, depths);
  // The exact curve first, at the probe's map size, then each technique.
  std::vector<std::string> specs = {"exact:size=" + std::to_string(mapSize)};
  specs.insert(specs.end(), p.shadows.begin(), p.shadows.end());
  std::vector<std::unique_ptr<ShadowTechnique>> techniques;
  for (const auto& spec : specs) techniques.push_back(makeShadowTechnique(Spec::parse(spec)));

  auto dev = makeRequestDevice(p.render);
  std::vector<std::vector<float>> curves;
  for (auto& t : techniques) {
    Renderer r(*dev, scene, settings, std::move(t), makeOitTechnique(Spec::parse("none")),
               {Output::Probe});
    r.renderFrame();
    curves.push_back(r.readProbe());
  }

  std::ostringstream f;
  f << "light_depth,x,y,z";
  for (const auto& s : specs) f << ",\"" << s << "\"";
  f << "\n";
  for (std::size_t i = 0; i < depths.size(); ++i) {
    const glm::vec3& w = settings.probePoints[i];
    f << depths[i] << "," << w.x << "," << w.y << "," << w.z;
    for (const auto& c : curves) f << "," << c[i];
    f << "\n";
  }
  writeFileAtomic(p.out, f.str());  // a failed run leaves no half file
  std::cout << "wrote " << p.out << ": " << depths.size() << " samples along light texel " << x
            << "," << y << " for " << specs.size() << " curves\n";
  return 0;
}

}  // namespace

void registerProbeCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "probe", "exact visibility along one light ray and each technique's reconstruction (CSV)");
  auto p = std::make_shared<ProbeRequest>();
  // The settings of the scene and the view (the ray is the light's), from the table.
  auto settings = std::make_shared<CliSettings>(
      *cmd,
      std::vector<std::string>{"scene", "backend", "platform", "size", "primitive", "ribbon_width",
                               "validation", "camera_eye", "camera_target", "camera_up", "fov",
                               "near", "far", "light", "light_position", "light_direction",
                               "light_color", "light_intensity"},
      p->render);
  cmd->add_option("--shadow", p->shadows,
                  "shadow technique spec (repeatable; none given: the exact curve alone)")
      ->capture_default_str();
  cmd->add_option("--texel", p->texel, "light texel X,Y")->capture_default_str();
  cmd->add_option("--map-size", p->mapSize, "light map size the texel refers to")
      ->capture_default_str();
  cmd->add_option("--samples", p->samples, "points along the ray")->capture_default_str();
  cmd->add_option("--out", p->out, "CSV file")->required();
  cmd->callback([p, settings] {
    runGuarded("probe", [&] {
      settings->apply(p->render);
      return runProbe(*p);
    });
  });
}

}  // namespace sb
