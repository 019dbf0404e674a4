// Scene catalog, option validation and the procedural generators (straight, wavy,
// curly, clustered hair on a spherical head; fur on a mesh) plus the file scene.
// Generators are deterministic for a seed: std::mt19937 with hand-written uniform
// mapping (std::uniform_real_distribution differs between standard libraries).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <new>
#include <numbers>
#include <optional>
#include <random>

#include "base/options.h"
#include "scenes/groom_rule.h"
#include "scenes/loader_util.h"
#include "scenes/mesh_loaders.h"
#include "scenes/scene.h"

namespace sb {

namespace {

constexpr uint64_t kMaxTotalPoints = 200'000'000;  // strands x points cap
constexpr int64_t kMaxStrands = 50'000'000;
constexpr int64_t kMaxPointsPerStrand = 100'000;
constexpr float kPi = std::numbers::pi_v<float>;

// ---------------------------------------------------------------- options

// Every scene's options in one struct; each scene's table (sceneKinds(), below) declares
// the ones it takes, with their ranges, defaults and help.
struct SceneOptions {
  std::string scene;  // the scene's name, for messages
  int64_t strands = 0;
  bool strandsGiven = false;  // fur: strands= or density=
  int points = 0;
  uint32_t seed = 1;
  float length = 0, thickness = 0, alpha = 1, shadowAlpha = 0.5f;
  std::string mesh;
  bool head = true;
  float amplitude = 0, frequency = 0, radius = 0, spread = 0, droop = 0, offset = 0, wiggle = 0;
  int64_t clusters = 0;
  std::optional<float> density;  // fur: strands per unit area
  std::string densityText;       // density= as given, for messages
  std::string path, up, color;   // file
  int64_t keep = 0;              // file: strands=; 0: all
  uint32_t pointsPerStrand = 0;  // file: 0 = not given
  float scale = 1;
  bool zeroSegments = false;
  // The groom (scenes/groom.h, docs/geometry.md): guides, the generation rule, a crowd.
  uint32_t guides = 0, instances = 1;
  float guideSpread = 0.5f, guideOffset = 0.5f, noise = 0.1f, clump = 0, lod = 1, lodPixels = 0;
  InputError error(const std::string& what) const {
    return InputError("scene '" + scene + "': " + what);
  }
};
using SO = SceneOptions;
// Refused while the options are read, before the scene is named: makeScene prefixes it.
struct UnnamedError : InputError {
  using InputError::InputError;
};
using SceneOption = std::vector<Option<SO>>;

// A number in (0, max]: a range with an open end, refused as "must be greater than 0".
SceneOption positive(float SO::*m, std::string name, std::string def, double max,
                     std::string help) {
  OptionInfo info = opt::number(name, std::move(def), 0.0, max, std::move(help));
  return {{std::move(info),
           [m, name](SO& s, const OptionReader& r) {
             const double v = r.number(name);
             if (!(v > 0.0))
               throw UnnamedError("option " + name + "=" + r.text(name) +
                                  " is out of range: must be greater than 0");
             s.*m = float(v);
           },
           [m](const SO& s) { return shortestNumber(s.*m); }}};
}

// An option that may be absent (its default empty): read, with its range, only when given.
SceneOption optional(std::string name, std::string help,
                     std::function<void(SO&, const OptionReader&)> fill,
                     std::function<std::string(const SO&)> show) {
  return {{opt::text(std::move(name), "", std::move(help)), std::move(fill), std::move(show)}};
}

// The 0/1 switches (head, zero_segments).
SceneOption zeroOne(bool SO::*m, std::string name, bool def, std::string help) {
  OptionInfo info = opt::integer(name, def ? 1 : 0, 0, 1, std::move(help));
  return {{std::move(info),
           [m, name](SO& s, const OptionReader& r) { s.*m = r.integer(name) == 1; },
           [m](const SO& s) { return std::string(s.*m ? "1" : "0"); }}};
}

SceneOption alphas() {
  return opt::group<SO>(
      {opt::number(&SO::alpha, "alpha", "1", 0.0, 1.0, "hair opacity in [0,1] for transparency"),
       opt::number(&SO::shadowAlpha, "shadow_alpha", "0.5", 0.0, 1.0,
                   "per-fragment shadow opacity in [0,1]")});
}

SceneOption commonOptions(long long strands, long long points, const char* length,
                          const char* lengthHelp, const char* meshHelp) {
  return opt::group<SO>(
      {opt::integer(&SO::strands, "strands", strands, 1, kMaxStrands, "number of strands"),
       opt::integer(&SO::points, "points", points, 2, kMaxPointsPerStrand,
                    "points per strand (>= 2)"),
       opt::integer(&SO::seed, "seed", 1, 0, std::numeric_limits<uint32_t>::max(),
                    "random seed (same seed, same scene)"),
       positive(&SO::length, "length", length, 100.0, lengthHelp),
       positive(&SO::thickness, "thickness", "0.005", 1000.0, "strand thickness in world units"),
       alphas(), opt::text(&SO::mesh, "mesh", "", meshHelp)});
}

constexpr const char* kMeshHelp =
    "mesh file drawn opaque (.obj, .ply, .tfxmesh; replaces the generated head)";

SceneOption hairOptions(long long strands, long long points, const char* length) {
  return opt::group<SO>({commonOptions(strands, points, length,
                                       "hair length in head radii (head radius is 1)", kMeshHelp),
                         zeroOne(&SO::head, "head", true,
                                 "1: draw the spherical head as the opaque mesh; 0: no head")});
}

void checkTotal(const SO& o, uint64_t strands, uint64_t points) {
  if (strands * points > kMaxTotalPoints) {
    throw o.error(std::to_string(strands) + " strands x " + std::to_string(points) +
                  " points = " + std::to_string(strands * points) +
                  " points exceeds the limit of " + std::to_string(kMaxTotalPoints));
  }
}

// "R/G/B", each in [0,1] (a spec's commas separate its options); "file": none.
std::optional<glm::vec3> colorOption(const SO& o) {
  const std::string& t = o.color;
  if (t == "file") return std::nullopt;
  float c[3];
  std::size_t at = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t end = i < 2 ? t.find('/', at) : t.size();
    char* stop = nullptr;
    const std::string part = end == std::string::npos ? "" : t.substr(at, end - at);
    c[i] = std::strtof(part.c_str(), &stop);
    if (part.empty() || *stop != '\0' || !(c[i] >= 0.0f && c[i] <= 1.0f))
      throw o.error("color=" + t + ": expected file or R/G/B, three numbers in [0,1]");
    at = end + 1;
  }
  return glm::vec3(c[0], c[1], c[2]);
}

// ---------------------------------------------------------------- random numbers

struct Rng {
  explicit Rng(uint32_t seed) : g(seed) {}
  // Uniform in [0, 1): the top 24 bits of one mt19937 output (identical everywhere).
  float u() { return float(g() >> 8) * (1.0f / 16777216.0f); }
  float range(float a, float b) { return a + (b - a) * u(); }
  std::mt19937 g;
};

// ---------------------------------------------------------------- geometry helpers

Mesh makeSphere(float radius, int slices, int stacks) {
  Mesh m;
  for (int i = 0; i <= stacks; ++i) {
    const float theta = kPi * float(i) / float(stacks);
    for (int j = 0; j <= slices; ++j) {
      const float phi = 2.0f * kPi * float(j) / float(slices);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                        std::sin(theta) * std::sin(phi));
      m.positions.push_back(radius * n);
      m.normals.push_back(n);
    }
  }
  const uint32_t row = uint32_t(slices + 1);
  for (uint32_t i = 0; i < uint32_t(stacks); ++i) {
    for (uint32_t j = 0; j < uint32_t(slices); ++j) {
      const uint32_t a = i * row + j, b = a + row, c = a + 1, d = b + 1;
      if (i != 0) m.indices.insert(m.indices.end(), {a, c, b});
      if (i + 1 != uint32_t(stacks)) m.indices.insert(m.indices.end(), {c, d, b});
    }
  }
  return m;
}

// Two unit vectors perpendicular to n and to each other.
void basis(const glm::vec3& n, glm::vec3& t1, glm::vec3& t2) {
  const glm::vec3 a = std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  t1 = glm::normalize(glm::cross(n, a));
  t2 = glm::cross(n, t1);
}

// A root direction on the scalp of the unit-sphere head (not the face, not below the ears).
glm::vec3 sampleScalp(Rng& rng) {
  for (;;) {
    const float z = rng.range(-1.0f, 1.0f);
    const float phi = rng.range(0.0f, 2.0f * kPi);
    const float rxy = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const glm::vec3 n(rxy * std::cos(phi), rxy * std::sin(phi), z);  // y up, z to the face
    const bool scalp = n.y > -0.2f && !(n.z > 0.35f && n.y < 0.55f);
    if (scalp) return n;
  }
}

void pushOut(glm::vec3& p, float radius) {
  const float len = glm::length(p);
  if (len < radius) p = len > 1e-6f ? p * (radius / len) : glm::vec3(0, radius, 0);
}

// Hair draped over the unit-sphere head: starts along the scalp, combed back and
// down, bent by gravity, kept outside a shell of radius 1 + layer. M segments.
std::vector<glm::vec3> growDraped(const glm::vec3& n, float length, float layer, int M) {
  std::vector<glm::vec3> c(std::size_t(M) + 1);
  glm::vec3 h(n.x, 0.0f, n.z);
  h += glm::vec3(0.0f, 0.0f, -0.5f);  // combed towards the back
  h = glm::dot(h, h) > 1e-8f ? glm::normalize(h) : glm::vec3(0, 0, -1);
  glm::vec3 dir = glm::normalize(0.5f * n + 0.85f * h);
  const float ds = length / float(M);
  const float gravity = 2.5f;  // turning per unit length
  const float shell = 1.0f + layer;
  glm::vec3 p = n;
  c[0] = p;
  for (int k = 1; k <= M; ++k) {
    dir = glm::normalize(dir + glm::vec3(0.0f, -gravity * ds, 0.0f));
    p += dir * ds;
    const float len = glm::length(p);
    if (len < shell) {
      const glm::vec3 radial = p / std::max(len, 1e-6f);
      p = radial * shell;
      const float inward = glm::dot(dir, radial);
      if (inward < 0.0f) {
        const glm::vec3 t = dir - inward * radial;  // slide along the head
        if (glm::dot(t, t) > 1e-8f) dir = glm::normalize(t);
      }
    }
    c[std::size_t(k)] = p;
  }
  return c;
}

// Adds offset(s, B1, B2) (s = arc length parameter in [0, length]) to a curve,
// using a parallel-transport frame, then keeps the curve outside the head.
void addOffsets(std::vector<glm::vec3>& c, float length, float shell,
                const std::function<glm::vec3(float, const glm::vec3&, const glm::vec3&)>& offset) {
  const std::size_t n = c.size();
  if (n < 2) return;
  std::vector<glm::vec3> base = c;
  glm::vec3 t = glm::normalize(base[1] - base[0]);
  glm::vec3 b1, b2;
  basis(t, b1, b2);
  for (std::size_t k = 0; k < n; ++k) {
    const glm::vec3 d = base[std::min(k + 1, n - 1)] - base[k > 0 ? k - 1 : 0];
    if (glm::dot(d, d) > 1e-12f) t = glm::normalize(d);
    glm::vec3 nb1 = b1 - glm::dot(b1, t) * t;
    if (glm::dot(nb1, nb1) > 1e-12f) b1 = glm::normalize(nb1);
    b2 = glm::cross(t, b1);
    const float s = length * float(k) / float(n - 1);
    // Ease in so that roots stay on the scalp.
    const float ramp = std::min(1.0f, s / (0.15f * length));
    c[k] = base[k] + ramp * ramp * (3.0f - 2.0f * ramp) * offset(s, b1, b2);
    if (k > 0) pushOut(c[k], shell);
  }
}

// Samples the fine curve at `points` evenly spaced parameters and appends a strand.
void appendStrand(Strands& out, const std::vector<glm::vec3>& fine, int points,
                  const glm::vec3& color, float thickness) {
  out.firstPoint.push_back(uint32_t(out.points.size()));
  out.pointCount.push_back(uint32_t(points));
  const float last = float(fine.size() - 1);
  for (int i = 0; i < points; ++i) {
    const float u = last * float(i) / float(points - 1);
    const std::size_t k = std::min(std::size_t(u), fine.size() - 2);
    const float f = u - float(k);
    out.points.push_back(glm::mix(fine[k], fine[k + 1], f));
    const float t = float(i) / float(points - 1);
    out.colors.push_back(glm::clamp(color * (1.0f + 0.12f * t), 0.0f, 1.0f));  // lighter tips
    out.thickness.push_back(thickness);
    out.transparency.push_back(0.0f);
  }
}

glm::vec3 strandColor(Rng& rng, const glm::vec3& base) {
  const float brightness = rng.range(0.85f, 1.15f);
  const glm::vec3 tint(rng.range(0.97f, 1.03f), rng.range(0.97f, 1.03f), rng.range(0.97f, 1.03f));
  return glm::clamp(base * brightness * tint, 0.0f, 1.0f);
}

void reserve(Strands& s, std::size_t strands, std::size_t points) {
  s.firstPoint.reserve(strands);
  s.pointCount.reserve(strands);
  s.points.reserve(strands * points);
  s.colors.reserve(strands * points);
  s.thickness.reserve(strands * points);
  s.transparency.reserve(strands * points);
}

// ---------------------------------------------------------------- scenes

// What every generated scene reads: the alphas into the scene, the total checked.
void readCommon(const SO& o, Scene& scene) {
  scene.hairAlpha = o.alpha;
  scene.shadowAlpha = o.shadowAlpha;
  checkTotal(o, uint64_t(o.strands), uint64_t(o.points));
}

void addHeadOrMesh(const SO& o, Scene& scene) {
  if (!o.mesh.empty()) {
    scene.mesh = loadMesh(o.mesh);
  } else if (o.head) {
    scene.mesh = makeSphere(1.0f, 48, 24);
  }
}

int fineSegments(int points) { return std::max(128, 4 * (points - 1)); }

enum class HairStyle { Straight, Wavy, Curly };

Scene makeHair(const SO& o, HairStyle style) {
  Scene scene;
  readCommon(o, scene);
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

Scene makeClustered(const SO& o) {
  Scene scene;
  readCommon(o, scene);
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

// Occupancy maps paper, Fig. 5a: a dense clump of vertical strands and, in
// front of it as seen from the default light (fitLight's direction), a single
// stray strand whose shadow falls across the clump: a thin occluder far from
// the others, which layer-based techniques place badly.
Scene makeStray(const SO& o) {
  Scene scene;
  readCommon(o, scene);
  const float radius = o.radius;
  const float offset = o.offset;
  if (!o.mesh.empty()) scene.mesh = loadMesh(o.mesh);
  Rng rng(o.seed);
  reserve(scene.strands, std::size_t(o.strands) + 1, std::size_t(o.points));
  auto vertical = [&](glm::vec2 xz, const glm::vec3& color) {
    const std::vector<glm::vec3> line = {{xz.x, 0.5f * o.length, xz.y},
                                         {xz.x, -0.5f * o.length, xz.y}};
    appendStrand(scene.strands, line, o.points, color, o.thickness);
  };
  for (int64_t k = 0; k < o.strands; ++k) {
    const float r = radius * std::sqrt(rng.u());
    const float phi = rng.range(0.0f, 2.0f * kPi);
    vertical({r * std::cos(phi), r * std::sin(phi)}, strandColor(rng, scene.hairColor));
  }
  // Towards the light: against fitLight()'s direction, in the horizontal plane.
  const glm::vec2 towardLight = glm::normalize(glm::vec2(1.0f, 0.8f));
  vertical(offset * towardLight, scene.hairColor);
  return scene;
}

Scene makeSheet(const SO& o) {
  Scene scene;
  readCommon(o, scene);
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

// The stiff-case options every scene has: a uniform scale and doubled points.
void applyScaleAndZeroSegments(const SO& o, Scene& scene) {
  const float scale = o.scale;
  if (scale != 1.0f) {
    for (auto& p : scene.strands.points) p *= scale;
    for (auto& t : scene.strands.thickness) t *= scale;
    for (auto& p : scene.mesh.positions) p *= scale;
  }
  if (!o.zeroSegments) return;
  Strands in = std::move(scene.strands), out;
  out.thicknessFallback = in.thicknessFallback;
  reserve(out, in.strandCount(), 2 * in.points.size() / std::max<std::size_t>(1, in.strandCount()));
  for (std::size_t k = 0; k < in.strandCount(); ++k) {
    out.firstPoint.push_back(uint32_t(out.points.size()));
    out.pointCount.push_back(2 * in.pointCount[k]);
    for (uint32_t i = in.firstPoint[k]; i < in.firstPoint[k] + in.pointCount[k]; ++i)
      for (int twice = 0; twice < 2; ++twice) {
        out.points.push_back(in.points[i]);
        out.colors.push_back(in.colors[i]);
        out.thickness.push_back(in.thickness[i]);
        out.transparency.push_back(in.transparency[i]);
      }
  }
  checkTotal(o, 1, out.points.size());
  scene.strands = std::move(out);
}

// The generation rule's shape: meaningful only with guides= (applyGroom refuses them without).
SceneOption groomShapeOptions() {
  return opt::group<SO>(
      {opt::number(&SO::guideSpread, "guide_spread", "0.5", 0.0, 1.0,
                   "guides=: how far a strand leans to a neighbouring guide, 0..1"),
       opt::number(&SO::guideOffset, "guide_offset", "0.5", 0.0, 10.0,
                   "guides=: per-strand offset in mean guide spacings, 0..10"),
       opt::number(&SO::noise, "noise", "0.1", 0.0, 10.0,
                   "guides=: per-point noise at the tip in mean guide spacings, 0..10"),
       opt::number(&SO::clump, "clump", "0", 0.0, 1.0,
                   "guides=: pull to the home guide at the tip, 0..1")});
}

// guides= and instances=: the groom kept with the scene, its strands made by the
// rule on the CPU, and the mesh repeated with every instance.
void applyGroom(const SO& o, Scene& scene) {
  GroomSettings g;
  g.guideEvery = o.guides;
  g.instances = o.instances;
  g.seed = o.seed;
  g.spread = o.guideSpread;
  g.offset = o.guideOffset;
  g.noise = o.noise;
  g.clump = o.clump;
  g.lod = o.lod;
  g.lodPixels = o.lodPixels;
  // The rule's shape options mean nothing without guides: refused rather than ignored
  // (any of them off its declared default).
  static const OptionTable<SO> shape({groomShapeOptions()});
  if (g.guideEvery == 0 && !shape.given(o).empty())
    throw o.error(
        "guide_spread=, guide_offset=, noise= and clump= need guides= (every n-th strand a "
        "guide)");
  if (g.lod < 1.0f && g.lodPixels > 0)
    throw o.error(
        "lod= (a fixed share) and lod_pixels= (a share by size on screen) are two "
        "levels of detail: give one");
  // The level of detail thins a groom: without guides every strand is its own.
  if (g.guideEvery == 0 && g.instances == 1 && g.lod == 1.0f && g.lodPixels == 0) return;
  scene.groom = makeGroom(scene.strands, g);
  checkTotal(o, 1, scene.groom.totalPoints());
  const bool fallback = scene.strands.thicknessFallback;
  scene.strands = generateStrands(scene.groom);
  scene.strands.thicknessFallback = fallback;
  if (g.instances == 1 || scene.mesh.positions.empty()) return;
  Mesh one = std::move(scene.mesh);
  Mesh& all = scene.mesh;
  for (const glm::vec4& place : scene.groom.placements) {
    const uint32_t base = uint32_t(all.positions.size());
    for (const glm::vec3& p : one.positions)
      all.positions.push_back(groom_rule::groomPlace(p, place));
    for (const glm::vec3& n : one.normals)
      all.normals.push_back(groom_rule::groomPlace(n, {place.x, place.y, 0.0f, 0.0f}));
    for (uint32_t i : one.indices) all.indices.push_back(base + i);
  }
}

Scene makeFur(const SO& o) {
  Scene scene;
  scene.hairAlpha = o.alpha;
  scene.shadowAlpha = o.shadowAlpha;
  SO c = o;  // strands: given, or from density= and the mesh's area
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

// up=auto for a format that does not say which way is up (PLY): the axis among y, z, -y
// and -z along which the strands' roots lie above their tips (hanging hair), when it is
// clear: the roots-to-tips offsets along it sum to at least kClearlyHanging of their
// lengths. Else y. Sets `why`.
constexpr double kClearlyHanging = 0.3;

std::string upFromRootsAndTips(const Strands& s, std::string& why) {
  glm::dvec3 sum(0.0);
  double length = 0;
  for (std::size_t i = 0; i < s.strandCount(); ++i) {
    if (s.pointCount[i] < 2) continue;
    const glm::dvec3 d = glm::dvec3(s.points[s.firstPoint[i]]) -
                         glm::dvec3(s.points[s.firstPoint[i] + s.pointCount[i] - 1]);
    sum += d;
    length += glm::length(d);
  }
  const std::pair<const char*, double> axes[] = {
      {"y", sum.y}, {"-y", -sum.y}, {"z", sum.z}, {"-z", -sum.z}};
  const auto* best = &axes[0];
  for (const auto& a : axes)
    if (a.second > best->second) best = &a;
  const double share = length > 0 ? best->second / length : 0.0;
  char pct[16];
  std::snprintf(pct, sizeof pct, "%.0f%%", 100.0 * std::max(share, 0.0));
  if (share < kClearlyHanging) {
    why = std::string(
              "auto: the format does not say, and roots and tips give no clear "
              "direction (the most, along ") +
          best->first + ", is " + pct + " of the strands' root-to-tip lengths): y";
    return "y";
  }
  why = std::string("auto: the format does not say; the roots lie above the tips along ") +
        best->first + " (" + pct + " of the strands' root-to-tip lengths), as hanging hair's";
  return best->first;
}

Scene makeFile(const SO& o) {
  Scene scene;
  const std::string& path = o.path;
  if (path.empty()) throw o.error("path= is required (a .hair, .tfx or .ply strand file)");
  scene.hairAlpha = o.alpha;
  scene.shadowAlpha = o.shadowAlpha;
  const int64_t keep = o.keep;                         // 0 = all
  const uint32_t pointsPerStrand = o.pointsPerStrand;  // 0 = not given
  std::string up = o.up;
  const std::optional<glm::vec3> color = colorOption(o);
  scene.frameByBox = true;
  const std::string& mesh = o.mesh;
  if (!mesh.empty()) scene.mesh = loadMesh(mesh);
  Strands all = loadStrandFile(path, pointsPerStrand, &scene.warnings);
  const auto extension = [&](const char* e) {
    const std::size_t n = std::strlen(e);
    return path.size() > n && path.compare(path.size() - n, n, e) == 0;
  };
  if (up != "auto") {
    scene.upReason = "up=" + up + " asked for";
  } else if (extension(".hair")) {
    up = "z";
    scene.upReason = "auto: the HAIR format's models (Yuksel's) are z-up";
  } else if (extension(".tfx")) {
    up = "y";
    scene.upReason = "auto: TressFX's models are y-up";
  } else {
    up = upFromRootsAndTips(all, scene.upReason);
  }
  scene.up = up;
  // The file's up axis turned to +y (a rotation about x, so handedness holds), the
  // strands and the mesh alike; its colours replaced where asked.
  const auto turn = [&](glm::vec3 p) {
    if (up == "z") return glm::vec3(p.x, p.z, -p.y);
    if (up == "-z") return glm::vec3(p.x, -p.z, p.y);
    if (up == "-y") return glm::vec3(p.x, -p.y, -p.z);
    return p;
  };
  if (up != "y") {
    for (glm::vec3& p : all.points) p = turn(p);
    for (glm::vec3& p : scene.mesh.positions) p = turn(p);
    for (glm::vec3& n : scene.mesh.normals) n = turn(n);
  }
  if (color)
    for (glm::vec3& c : all.colors) c = *color;
  if (keep == 0 || uint64_t(keep) == all.strandCount()) {
    scene.strands = std::move(all);
    return scene;
  }
  if (uint64_t(keep) > all.strandCount()) {
    throw o.error("strands=" + std::to_string(keep) + " exceeds the " +
                  std::to_string(all.strandCount()) + " strands in " + path);
  }
  Strands& out = scene.strands;
  out.thicknessFallback = all.thicknessFallback;
  const uint64_t total = all.strandCount();
  for (uint64_t i = 0; i < uint64_t(keep); ++i) {
    const std::size_t s = std::size_t(i * total / uint64_t(keep));
    const uint32_t first = all.firstPoint[s], count = all.pointCount[s];
    out.firstPoint.push_back(uint32_t(out.points.size()));
    out.pointCount.push_back(count);
    out.points.insert(out.points.end(), all.points.begin() + first,
                      all.points.begin() + first + count);
    out.colors.insert(out.colors.end(), all.colors.begin() + first,
                      all.colors.begin() + first + count);
    out.thickness.insert(out.thickness.end(), all.thickness.begin() + first,
                         all.thickness.begin() + first + count);
    out.transparency.insert(out.transparency.end(), all.transparency.begin() + first,
                            all.transparency.begin() + first + count);
  }
  return scene;
}

// The groom every scene may have (applyGroom): guides, the generation rule's shape
// (groomShapeOptions, above), a crowd.
SceneOption groomOptions() {
  return opt::group<SO>(
      {opt::integer(&SO::guides, "guides", 0, 0, kMaxStrands,
                    "every n-th strand is a guide and the strands are made from the guides by "
                    "the generation rule (docs/geometry.md); 0: no guides"),
       groomShapeOptions(),
       positive(&SO::lod, "lod", "1", 1.0,
                "level of detail: the share of each instance's strands kept (0..1], their "
                "thickness widened by the strands left out (docs/geometry.md)"),
       opt::number(&SO::lodPixels, "lod_pixels", "0", 0.0, 100000.0,
                   "level of detail by size on screen: an instance spanning s pixels keeps "
                   "min(1, (s/lod_pixels)^2) of its strands, widened to match; 0: off"),
       opt::integer(&SO::instances, "instances", 1, 1, 10000,
                    "copies of the groom in a grid on the floor, each turned and made with its "
                    "own seed, 1..10000")});
}

// A scene: its options' table and how it is made.
struct SceneKind {
  std::string name, help;
  OptionTable<SO> options;
  std::function<Scene(const SO&)> make;
};

const std::vector<SceneKind>& sceneKinds() {
  // The stiff cases every scene has: extreme scales and degenerate segments.
  const SceneOption stiff =
      opt::group<SO>({opt::number(&SO::scale, "scale", "1", 1e-6, 1e6,
                                  "uniform scale of the whole scene, 1e-6..1e6"),
                      zeroOne(&SO::zeroSegments, "zero_segments", false,
                              "1: every point doubled (every other segment has zero length)"),
                      groomOptions()});
  const auto hair = [&](const char* name, const char* help, long long strands, long long points,
                        const char* length, SceneOption own, HairStyle style) {
    return SceneKind{name, help,
                     OptionTable<SO>({hairOptions(strands, points, length), own, stiff}),
                     [style](const SO& o) { return makeHair(o, style); }};
  };
  const SceneOption frequency =
      opt::number(&SO::frequency, "frequency", "3", 0.0, 1000.0, "waves per unit of hair length");
  static const std::vector<SceneKind> kinds = {
      hair("straight", "straight hair on a spherical head, draped by gravity", 2000, 16, "1.5", {},
           HairStyle::Straight),
      hair("wavy", "wavy hair: straight hair with a sinusoidal wave", 2000, 24, "1.5",
           opt::group<SO>({opt::number(&SO::amplitude, "amplitude", "0.06", 0.0, 10.0,
                                       "wave amplitude in head radii"),
                           frequency}),
           HairStyle::Wavy),
      hair("curly", "curly hair: helical curls around a draped strand", 1500, 48, "1.2",
           opt::group<SO>(
               {opt::number(&SO::radius, "radius", "0.05", 0.0, 10.0, "curl radius in head radii"),
                opt::number(&SO::frequency, "frequency", "5", 0.0, 1000.0,
                            "curl turns per unit of hair length")}),
           HairStyle::Curly),
      {"clustered", "hair grouped into tight clumps that converge to their tips",
       OptionTable<SO>({hairOptions(2000, 16, "1.5"),
                        opt::integer(&SO::clusters, "clusters", 64, 1, kMaxStrands,
                                     "number of clumps (<= strands)"),
                        opt::number(&SO::spread, "spread", "0.1", 0.0, 10.0,
                                    "clump radius at the scalp in head radii"),
                        stiff}),
       makeClustered},
      {"fur", "fur grown along a mesh's normals",
       OptionTable<SO>(
           {commonOptions(
                20000, 6,
                "0.1", "fur length as a fraction of the base mesh's bounding radius",
                "mesh to grow fur on (.obj, .ply, .tfxmesh), drawn opaque (default: a unit "
                "sphere)"),
            opt::number(&SO::droop, "droop", "0.5", 0.0, 100.0,
                        "gravity bend of the fur (0 = straight along the normal)"),
            optional(
                "density", "strands per unit of mesh area (replaces strands=)",
                [](SO& s, const OptionReader& r) {
                  if (!r.has("density")) return;
                  if (r.has("strands"))
                    throw UnnamedError(
                        "give strands= (total) or density= (per unit area), not both");
                  const double v = r.number("density", 0.0, 1e12);
                  if (!(v > 0.0))
                    throw UnnamedError("option density=" + r.text("density") +
                                       " is out of range: must be greater than 0");
                  s.density = float(v);
                  s.densityText = r.text("density");
                },
                [](const SO& s) { return s.densityText; }),
            stiff}),
       makeFur},
      {"stray", "one strand between the light and a dense clump (the occupancy-map paper, Fig. 5a)",
       OptionTable<SO>(
           {commonOptions(3000, 16, "1", "length of the clump's strands (world units)", kMeshHelp),
            positive(&SO::radius, "radius", "0.15", 100.0, "radius of the dense clump"),
            opt::number(&SO::offset, "offset", "0.45", 0.0, 100.0,
                        "distance of the stray strand from the clump's axis, towards "
                        "the default light"),
            stiff}),
       makeStray},
      {"sheet",
       "strands in the plane z = 0: lit along -z, every fragment of a light texel is at one depth "
       "(a zero depth range)",
       OptionTable<SO>({commonOptions(200, 16, "2", "strand length (world units)", kMeshHelp),
                        opt::number(&SO::wiggle, "wiggle", "0.1", 0.0, 100.0,
                                    "zigzag amplitude in the plane (strands cross each other)"),
                        stiff}),
       makeSheet},
      {"file", "strands from a file (.hair, .tfx, .ply), optionally with a mesh",
       OptionTable<SO>(
           {opt::text(&SO::path, "path", "", "strand file (required): .hair, .tfx or .ply"),
            opt::text(&SO::mesh, "mesh", "", "mesh file drawn opaque (.obj, .ply, .tfxmesh)"),
            {{opt::text("strands", "all", "keep this many strands, evenly spaced (default: all)"),
              [](SO& s, const OptionReader& r) {
                s.keep = r.text("strands") == "all" ? 0 : r.integer("strands", 1, kMaxStrands);
              },
              [](const SO& s) { return s.keep ? std::to_string(s.keep) : "all"; }}},
            optional(
                "points_per_strand",
                "PLY without a 'strand' element (e.g. NeuralHaircut): strands of N "
                "consecutive vertices, 2.." +
                    std::to_string(kMaxPointsPerStrand),
                [](SO& s, const OptionReader& r) {
                  if (r.has("points_per_strand"))
                    s.pointsPerStrand =
                        uint32_t(r.integer("points_per_strand", 2, kMaxPointsPerStrand));
                },
                [](const SO& s) {
                  return s.pointsPerStrand ? std::to_string(s.pointsPerStrand) : "";
                }),
            alphas(),
            opt::integer(&SO::seed, "seed", 1, 0, std::numeric_limits<uint32_t>::max(),
                         "seed of the generation rule (guides=, instances=)"),
            opt::choice(&SO::up, "up", "auto", {"auto", "y", "z", "-y", "-z"},
                        "the file's up axis, turned to +y: auto (z for .hair, Yuksel's models are "
                        "z-up; y for .tfx, TressFX's; for .ply, which does not say, the axis "
                        "along which the roots lie above the tips, as hanging hair's do, else "
                        "y), y, z, -y or -z; the render JSON's scene.up and up_reason"),
            opt::text(&SO::color, "color", "file",
                      "strand colours: file (the file's own, where it has them) or R/G/B in "
                      "[0,1] for every strand (color=0.45/0.3/0.18)"),
            stiff}),
       makeFile},
  };
  return kinds;
}

}  // namespace

const std::vector<SceneInfo>& sceneCatalog() {
  static const std::vector<SceneInfo> catalog = [] {
    std::vector<SceneInfo> c;
    for (const SceneKind& k : sceneKinds()) c.push_back({k.name, k.help, k.options.infos()});
    return c;
  }();
  return catalog;
}

Scene makeScene(const Spec& spec) {
  const SceneKind* kind = nullptr;
  std::vector<std::string> names;
  for (const SceneKind& k : sceneKinds()) {
    names.push_back(k.name);
    if (k.name == spec.name) kind = &k;
  }
  if (!kind) throw InputError(unknownNameMessage("scene", spec.name, names));
  SO o;
  try {
    o = kind->options.read(spec, "scene '" + kind->name + "'");
  } catch (const UnnamedError& e) {
    throw InputError("scene '" + kind->name + "': " + e.what());
  }
  o.scene = kind->name;
  Scene scene;
  try {
    scene = kind->make(o);
  } catch (const std::bad_alloc&) {
    throw OutOfMemoryError("out of memory building scene " + spec.str() +
                           ": a host allocation failed (points, colours and segment arrays; "
                           "fewer strands= or points= make it fit)");
  }
  applyScaleAndZeroSegments(o, scene);
  applyGroom(o, scene);
  scene.name = spec.str();
  return scene;
}

Scene withLevelOfDetail(const Scene& full, const Camera& camera, uint32_t imageHeight) {
  Scene s;  // all but the strands, which the rule makes again
  s.name = full.name;
  s.mesh = full.mesh;
  s.hairAlpha = full.hairAlpha;
  s.shadowAlpha = full.shadowAlpha;
  s.hairColor = full.hairColor;
  s.frameByBox = full.frameByBox;
  s.warnings = full.warnings;
  s.up = full.up;
  s.upReason = full.upReason;
  s.groom = full.groom;
  groomLevelOfDetail(s.groom, camera, imageHeight);
  s.strands = generateStrands(s.groom);
  s.strands.thicknessFallback = full.strands.thicknessFallback;
  return s;
}

}  // namespace sb
