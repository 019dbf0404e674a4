// What the generated scenes share (the units under scenes/generators/ that grow strands
// rather than read them): their common options, a portable random number generator and the
// geometry that drapes, curls and samples strands. Generators are deterministic for a seed:
// std::mt19937 with hand-written uniform mapping (std::uniform_real_distribution differs
// between standard libraries).
#pragma once

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <numbers>
#include <random>
#include <vector>

#include "scenes/scene_unit.h"

namespace sb {

inline constexpr float kPi = std::numbers::pi_v<float>;

// The options of a generated scene: how many strands of how many points, how long and thick,
// and whether the spherical head is drawn.
struct GeneratedScene : SceneBase {
  int64_t strands = 0;
  int points = 0;
  float length = 0, thickness = 0;
  bool head = true;
};

inline constexpr const char* kMeshHelp =
    "mesh file drawn opaque (.obj, .ply, .tfxmesh; replaces the generated head)";

// strands=, points=, seed=, length=, thickness=, alpha=, shadow_alpha= and mesh=, with this
// scene's defaults and help.
std::vector<Option<GeneratedScene>> generatedOptions(long long strands, long long points,
                                                     const char* length, const char* lengthHelp,
                                                     const char* meshHelp);
// generatedOptions with the hair's length help and mesh help, and head=.
std::vector<Option<GeneratedScene>> hairOptions(long long strands, long long points,
                                                const char* length);

// The total checked (strands x points).
void checkGenerated(const GeneratedScene& o);
// The mesh= file, else the unit-sphere head where head=1.
void addHeadOrMesh(const GeneratedScene& o, Scene& scene);

struct Rng {
  explicit Rng(uint32_t seed) : g(seed) {}
  // Uniform in [0, 1): the top 24 bits of one mt19937 output (identical everywhere).
  float u() { return float(g() >> 8) * (1.0f / 16777216.0f); }
  float range(float a, float b) { return a + (b - a) * u(); }
  std::mt19937 g;
};

Mesh makeSphere(float radius, int slices, int stacks);
// Two unit vectors perpendicular to n and to each other.
void basis(const glm::vec3& n, glm::vec3& t1, glm::vec3& t2);
// A root direction on the scalp of the unit-sphere head (not the face, not below the ears).
glm::vec3 sampleScalp(Rng& rng);
// p moved out to `radius` from the origin where it is inside.
void pushOut(glm::vec3& p, float radius);
// Hair draped over the unit-sphere head: starts along the scalp, combed back and
// down, bent by gravity, kept outside a shell of radius 1 + layer. M segments.
std::vector<glm::vec3> growDraped(const glm::vec3& n, float length, float layer, int M);
// Adds offset(s, B1, B2) (s = arc length parameter in [0, length]) to a curve,
// using a parallel-transport frame, then keeps the curve outside the head.
void addOffsets(std::vector<glm::vec3>& c, float length, float shell,
                const std::function<glm::vec3(float, const glm::vec3&, const glm::vec3&)>& offset);
// Samples the fine curve at `points` evenly spaced parameters and appends a strand.
void appendStrand(Strands& out, const std::vector<glm::vec3>& fine, int points,
                  const glm::vec3& color, float thickness);
glm::vec3 strandColor(Rng& rng, const glm::vec3& base);
// The segments of the fine curve a strand of `points` is sampled from.
inline int fineSegments(int points) { return std::max(128, 4 * (points - 1)); }

}  // namespace sb
