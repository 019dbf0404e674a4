// Strands in the plane z = 0, lit along -z: every fragment of a light texel is at one depth
// (a zero depth range), the stiff case of the depth-bounded techniques.
#include "scenes/generated.h"
#include "scenes/mesh_loaders.h"

namespace sb {
namespace {

struct SheetOptions : GeneratedScene {
  float wiggle = 0;
};

Scene makeSheet(const SheetOptions& o) {
  Scene scene;
  checkGenerated(o);
  const float wiggle = o.wiggle;
  if (!o.mesh.empty()) scene.mesh = loadMesh(o.mesh);
  Rng rng(o.seed);
  reserve(scene.strands, std::size_t(o.strands), std::size_t(o.points));
  for (int64_t k = 0; k < o.strands; ++k) {
    const float x = o.strands > 1 ? -1.0f + 2.0f * float(k) / float(o.strands - 1) : 0.0f;
    std::vector<glm::vec3> zigzag;
    for (int i = 0; i < o.points; ++i) {
      const float t = float(i) / float(o.points - 1);
      const float side = (i % 2 ? 1.0f : -1.0f) * wiggle;
      zigzag.push_back({x + side, 0.5f * o.length - t * o.length, 0.0f});
    }
    appendStrand(scene.strands, zigzag, o.points, strandColor(rng, scene.hairColor), o.thickness);
  }
  return scene;
}

}  // namespace
}  // namespace sb

SB_SCENE(sceneUnit<SheetOptions>(
    "sheet",
    "strands in the plane z = 0: lit along -z, every fragment of a light texel is at one depth "
    "(a zero depth range)",
    6,
    {opt::inherited<SheetOptions>(generatedOptions(200, 16, "2", "strand length (world units)",
                                                   kMeshHelp)),
     opt::number(&SheetOptions::wiggle, "wiggle", "0.1", 0.0, 100.0,
                 "zigzag amplitude in the plane (strands cross each other)")},
    makeSheet));
