// Fur grown along a mesh's normals (a unit sphere by default), bent by gravity, its count
// given in total or per unit of the mesh's area.
#include <algorithm>
#include <cmath>
#include <optional>

#include "scenes/generated.h"
#include "scenes/mesh_loaders.h"

namespace sb {
namespace {

struct FurOptions : GeneratedScene {
  float droop = 0;
  std::optional<float> density;  // strands per unit area
  std::string densityText;       // density= as given, for messages
};
using FO = FurOptions;

Scene makeFur(const FO& o) {
  Scene scene;
  FO c = o;  // strands: given, or from density= and the mesh's area
  const float droop = o.droop;
  const bool useDensity = o.density.has_value();
  const float density = o.density.value_or(0.0f);
  const std::string meshPath = o.mesh;
  scene.mesh = meshPath.empty() ? makeSphere(1.0f, 64, 32) : loadMesh(meshPath);
  const Mesh& mesh = scene.mesh;

  // Area table for uniform sampling over the surface.
  const std::size_t tris = mesh.triangleCount();
  std::vector<double> cumulative(tris);
  double area = 0.0;
  for (std::size_t t = 0; t < tris; ++t) {
    const glm::vec3& a = mesh.positions[mesh.indices[3 * t]];
    const glm::vec3& b = mesh.positions[mesh.indices[3 * t + 1]];
    const glm::vec3& d = mesh.positions[mesh.indices[3 * t + 2]];
    area += 0.5 * double(glm::length(glm::cross(b - a, d - a)));
    cumulative[t] = area;
  }
  if (!(area > 0.0) || !std::isfinite(area)) throw o.error("the fur mesh has no surface area");
  if (useDensity) {
    const double n = std::round(double(density) * area);
    if (n > double(kMaxStrands)) {
      throw o.error("density=" + o.densityText + " over an area of " + std::to_string(area) +
                    " gives more than " + std::to_string(kMaxStrands) + " strands");
    }
    c.strands = std::max<int64_t>(1, int64_t(n));
  }
  checkTotal(o, uint64_t(c.strands), uint64_t(c.points));

  Bounds mb;
  mb.min = mb.max = mesh.positions.empty() ? glm::vec3(0.0f) : mesh.positions[0];
  for (const glm::vec3& p : mesh.positions) {
    mb.min = glm::min(mb.min, p);
    mb.max = glm::max(mb.max, p);
  }
  const float furLength = c.length * mb.radius();
  Rng rng(c.seed);
  reserve(scene.strands, std::size_t(c.strands), std::size_t(c.points));
  std::vector<glm::vec3> pts(std::size_t(c.points));
  for (int64_t s = 0; s < c.strands; ++s) {
    const double x = double(rng.u()) * area;
    const std::size_t tri = std::min<std::size_t>(
        std::size_t(std::upper_bound(cumulative.begin(), cumulative.end(), x) - cumulative.begin()),
        tris - 1);
    const uint32_t ia = mesh.indices[3 * tri], ib = mesh.indices[3 * tri + 1],
                   ic = mesh.indices[3 * tri + 2];
    const float r1 = std::sqrt(rng.u()), r2 = rng.u();
    const float wa = 1.0f - r1, wb = r1 * (1.0f - r2), wc = r1 * r2;
    const glm::vec3 root =
        wa * mesh.positions[ia] + wb * mesh.positions[ib] + wc * mesh.positions[ic];
    glm::vec3 n = wa * mesh.normals[ia] + wb * mesh.normals[ib] + wc * mesh.normals[ic];
    if (!(glm::dot(n, n) > 1e-12f)) {
      n = glm::cross(mesh.positions[ib] - mesh.positions[ia],
                     mesh.positions[ic] - mesh.positions[ia]);
    }
    n = glm::dot(n, n) > 1e-30f ? glm::normalize(n) : glm::vec3(0, 1, 0);
    const float length = furLength * rng.range(0.8f, 1.2f);
    const glm::vec3 color = strandColor(rng, scene.hairColor);
    const float ds = length / float(c.points - 1);
    // Gravity's component along the surface bends the fur; it never turns it back
    // into the surface (fur on top stands, fur on the sides droops).
    const glm::vec3 gravity(0.0f, -1.0f, 0.0f);
    const glm::vec3 tangential = gravity - glm::dot(gravity, n) * n;
    pts[0] = root;
    for (int i = 1; i < c.points; ++i) {
      const float t = (float(i) - 0.5f) / float(c.points - 1);
      const glm::vec3 dir = glm::normalize(n + droop * t * tangential);
      pts[std::size_t(i)] = pts[std::size_t(i) - 1] + dir * ds;
    }
    Strands& out = scene.strands;
    out.firstPoint.push_back(uint32_t(out.points.size()));
    out.pointCount.push_back(uint32_t(c.points));
    for (int i = 0; i < c.points; ++i) {
      const float t = float(i) / float(c.points - 1);
      out.points.push_back(pts[std::size_t(i)]);
      out.colors.push_back(glm::clamp(color * (1.0f + 0.12f * t), 0.0f, 1.0f));
      out.thickness.push_back(c.thickness);
      out.transparency.push_back(0.0f);
    }
  }
  return scene;
}

}  // namespace
}  // namespace sb

SB_SCENE(sceneUnit<FO>(
    "fur", "fur grown along a mesh's normals", 4,
    {opt::inherited<FO>(generatedOptions(
         20000, 6, "0.1", "fur length as a fraction of the base mesh's bounding radius",
         "mesh to grow fur on (.obj, .ply, .tfxmesh), drawn opaque (default: a unit sphere)")),
     opt::number(&FO::droop, "droop", "0.5", 0.0, 100.0,
                 "gravity bend of the fur (0 = straight along the normal)"),
     scene_opt::optional<FO>(
         "density", "strands per unit of mesh area (replaces strands=)",
         [](FO& s, const OptionReader& r) {
           if (!r.has("density")) return;
           if (r.has("strands"))
             throw UnnamedSceneError("give strands= (total) or density= (per unit area), not both");
           const double v = r.number("density", 0.0, 1e12);
           if (!(v > 0.0))
             throw UnnamedSceneError("option density=" + r.text("density") +
                                     " is out of range: must be greater than 0");
           s.density = float(v);
           s.densityText = r.text("density");
         },
         [](const FO& s) { return s.densityText; })},
    makeFur));
