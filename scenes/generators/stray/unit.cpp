// Occupancy maps paper, Fig. 5a: a dense clump of vertical strands and, in front of it as
// seen from the default light (fitLight's direction), a single stray strand whose shadow falls
// across the clump: a thin occluder far from the others, which layer-based techniques place
// badly.
#include <cmath>

#include "scenes/generated.h"
#include "scenes/mesh_loaders.h"

namespace sb {
namespace {

struct StrayOptions : GeneratedScene {
  float radius = 0, offset = 0;
};
using SO = StrayOptions;

Scene makeStray(const SO& o) {
  Scene scene;
  checkGenerated(o);
  if (!o.mesh.empty()) scene.mesh = loadMesh(o.mesh);
  Rng rng(o.seed);
  reserve(scene.strands, std::size_t(o.strands) + 1, std::size_t(o.points));
  auto vertical = [&](glm::vec2 xz, const glm::vec3& color) {
    const std::vector<glm::vec3> line = {{xz.x, 0.5f * o.length, xz.y},
                                         {xz.x, -0.5f * o.length, xz.y}};
    appendStrand(scene.strands, line, o.points, color, o.thickness);
  };
  for (int64_t k = 0; k < o.strands; ++k) {
    const float r = o.radius * std::sqrt(rng.u());
    const float phi = rng.range(0.0f, 2.0f * kPi);
    vertical({r * std::cos(phi), r * std::sin(phi)}, strandColor(rng, scene.hairColor));
  }
  // Towards the light: against fitLight()'s direction, in the horizontal plane.
  const glm::vec2 towardLight = glm::normalize(glm::vec2(1.0f, 0.8f));
  vertical(o.offset * towardLight, scene.hairColor);
  return scene;
}

}  // namespace
}  // namespace sb

SB_SCENE(sceneUnit<SO>(
    "stray", "one strand between the light and a dense clump (the occupancy-map paper, Fig. 5a)", 5,
    {opt::inherited<SO>(generatedOptions(3000, 16, "1",
                                         "length of the clump's strands (world units)", kMeshHelp)),
     scene_opt::positive(&SO::radius, "radius", "0.15", 100.0, "radius of the dense clump"),
     opt::number(&SO::offset, "offset", "0.45", 0.0, 100.0,
                 "distance of the stray strand from the clump's axis, towards the default light")},
    makeStray));
