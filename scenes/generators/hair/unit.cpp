// Hair on a spherical head: straight, wavy and curly, draped by gravity (three scenes, one
// way of growing them).
#include <cmath>

#include "scenes/generated.h"

namespace sb {
namespace {

struct HairOptions : GeneratedScene {
  float amplitude = 0, frequency = 0, radius = 0;  // wavy: amplitude, frequency; curly: radius
};
using HO = HairOptions;

enum class HairStyle { Straight, Wavy, Curly };

Scene makeHair(const HO& o, HairStyle style) {
  Scene scene;
  checkGenerated(o);
  const float amplitude = o.amplitude, frequency = o.frequency, radius = o.radius;
  addHeadOrMesh(o, scene);
  Rng rng(o.seed);
  const int M = fineSegments(o.points);
  reserve(scene.strands, std::size_t(o.strands), std::size_t(o.points));
  for (int64_t s = 0; s < o.strands; ++s) {
    const glm::vec3 root = sampleScalp(rng);
    const float length = o.length * rng.range(0.9f, 1.1f);
    const float layer = rng.range(0.015f, 0.075f);
    const float phase = rng.range(0.0f, 2.0f * kPi);
    const glm::vec3 color = strandColor(rng, scene.hairColor);
    std::vector<glm::vec3> fine = growDraped(root, length, layer, M);
    if (style == HairStyle::Wavy) {
      addOffsets(fine, length, 1.0f + 0.5f * layer,
                 [&](float t, const glm::vec3& b1, const glm::vec3&) {
                   return amplitude * std::sin(2.0f * kPi * frequency * t + phase) * b1;
                 });
    } else if (style == HairStyle::Curly) {
      addOffsets(fine, length, 1.0f + 0.5f * layer,
                 [&](float t, const glm::vec3& b1, const glm::vec3& b2) {
                   const float a = 2.0f * kPi * frequency * t + phase;
                   return radius * (std::cos(a) * b1 + std::sin(a) * b2);
                 });
    }
    appendStrand(scene.strands, fine, o.points, color, o.thickness);
  }
  return scene;
}

// One style's scene: the hair's options with its defaults, then the style's own.
SceneDescriptor hair(const char* name, const char* help, int order, long long strands,
                     long long points, const char* length, std::vector<Option<HO>> own,
                     HairStyle style) {
  return sceneUnit<HO>(name, help, order,
                       {opt::inherited<HO>(hairOptions(strands, points, length)), std::move(own)},
                       [style](const HO& o) { return makeHair(o, style); });
}

}  // namespace
}  // namespace sb

SB_SCENE(hair("straight", "straight hair on a spherical head, draped by gravity", 0, 2000, 16,
              "1.5", {}, HairStyle::Straight));
SB_SCENE(hair("wavy", "wavy hair: straight hair with a sinusoidal wave", 1, 2000, 24, "1.5",
              opt::group<HO>({opt::number(&HO::amplitude, "amplitude", "0.06", 0.0, 10.0,
                                          "wave amplitude in head radii"),
                              opt::number(&HO::frequency, "frequency", "3", 0.0, 1000.0,
                                          "waves per unit of hair length")}),
              HairStyle::Wavy));
SB_SCENE(hair("curly", "curly hair: helical curls around a draped strand", 2, 1500, 48, "1.2",
              opt::group<HO>({opt::number(&HO::radius, "radius", "0.05", 0.0, 10.0,
                                          "curl radius in head radii"),
                              opt::number(&HO::frequency, "frequency", "5", 0.0, 1000.0,
                                          "curl turns per unit of hair length")}),
              HairStyle::Curly));
