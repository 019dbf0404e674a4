// Hair grouped into tight clumps that converge to their tips.
#include <cmath>

#include "scenes/generated.h"

namespace sb {
namespace {

struct ClusteredOptions : GeneratedScene {
  int64_t clusters = 0;
  float spread = 0;
};
using CO = ClusteredOptions;

Scene makeClustered(const CO& o) {
  Scene scene;
  checkGenerated(o);
  const int64_t clusters = o.clusters;
  const float spread = o.spread;
  if (clusters > o.strands) {
    throw o.error("clusters=" + std::to_string(clusters) +
                  " exceeds strands=" + std::to_string(o.strands));
  }
  addHeadOrMesh(o, scene);
  Rng rng(o.seed);
  const int M = fineSegments(o.points);
  reserve(scene.strands, std::size_t(o.strands), std::size_t(o.points));
  for (int64_t k = 0; k < clusters; ++k) {
    const int64_t members = o.strands / clusters + (k < o.strands % clusters ? 1 : 0);
    const glm::vec3 root = sampleScalp(rng);
    const float length = o.length * rng.range(0.9f, 1.1f);
    const float layer = rng.range(0.015f, 0.075f);
    const glm::vec3 clumpColor = strandColor(rng, scene.hairColor);
    const std::vector<glm::vec3> guide = growDraped(root, length, layer, M);
    glm::vec3 t1, t2;
    basis(root, t1, t2);
    std::vector<glm::vec3> fine(guide.size());
    for (int64_t m = 0; m < members; ++m) {
      const float r = spread * std::sqrt(rng.u());
      const float phi = rng.range(0.0f, 2.0f * kPi);
      const glm::vec3 memberRoot =
          glm::normalize(root + r * (std::cos(phi) * t1 + std::sin(phi) * t2));
      const glm::vec3 delta = memberRoot - root;
      const float tight = rng.range(0.75f, 0.95f);  // how close to the guide the tip ends
      const glm::vec3 color = glm::clamp(clumpColor * rng.range(0.95f, 1.05f), 0.0f, 1.0f);
      for (std::size_t i = 0; i < guide.size(); ++i) {
        const float t = float(i) / float(guide.size() - 1);
        fine[i] = guide[i] + delta * (1.0f - tight * t);
        if (i > 0) pushOut(fine[i], 1.01f);
      }
      fine[0] = memberRoot;
      appendStrand(scene.strands, fine, o.points, color, o.thickness);
    }
  }
  return scene;
}

}  // namespace
}  // namespace sb

SB_SCENE(sceneUnit<CO>("clustered", "hair grouped into tight clumps that converge to their tips", 3,
                       {opt::inherited<CO>(hairOptions(2000, 16, "1.5")),
                        opt::integer(&CO::clusters, "clusters", 64, 1, kMaxStrands,
                                     "number of clumps (<= strands)"),
                        opt::number(&CO::spread, "spread", "0.1", 0.0, 10.0,
                                    "clump radius at the scalp in head radii")},
                       makeClustered));
