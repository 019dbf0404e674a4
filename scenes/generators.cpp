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

#include "scenes/groom_rule.h"
#include "scenes/loader_util.h"
#include "scenes/mesh_loaders.h"
#include "scenes/options.h"
#include "scenes/scene.h"

namespace sb {

namespace {

constexpr uint64_t kMaxTotalPoints = 200'000'000;  // strands x points cap
constexpr int64_t kMaxStrands = 50'000'000;
constexpr int64_t kMaxPointsPerStrand = 100'000;
constexpr float kPi = std::numbers::pi_v<float>;

// ---------------------------------------------------------------- catalog

std::vector<OptionInfo> commonOptions(const char* strands, const char* points, const char* length,
                                      const char* lengthHelp) {
  return {
      {"strands", strands, "number of strands"},
      {"points", points, "points per strand (>= 2)"},
      {"seed", "1", "random seed (same seed, same scene)"},
      {"length", length, lengthHelp},
      {"thickness", "0.005", "strand thickness in world units"},
      {"alpha", "1", "hair opacity in [0,1] for transparency"},
      {"shadow_alpha", "0.5", "per-fragment shadow opacity in [0,1]"},
      {"mesh", "", "mesh file drawn opaque (.obj, .ply, .tfxmesh; replaces the generated head)"},
  };
}

std::vector<OptionInfo> hairOptions(const char* strands, const char* points, const char* length,
                                    std::vector<OptionInfo> extra) {
  std::vector<OptionInfo> o =
      commonOptions(strands, points, length, "hair length in head radii (head radius is 1)");
  o.push_back({"head", "1", "1: draw the spherical head as the opaque mesh; 0: no head"});
  o.insert(o.end(), extra.begin(), extra.end());
  return o;
}

std::vector<SceneInfo> buildCatalog() {
  std::vector<SceneInfo> c;
  c.push_back({"straight", "straight hair on a spherical head, draped by gravity",
               hairOptions("2000", "16", "1.5", {})});
  c.push_back({"wavy", "wavy hair: straight hair with a sinusoidal wave",
               hairOptions("2000", "24", "1.5",
                           {{"amplitude", "0.06", "wave amplitude in head radii"},
                            {"frequency", "3", "waves per unit of hair length"}})});
  c.push_back({"curly", "curly hair: helical curls around a draped strand",
               hairOptions("1500", "48", "1.2",
                           {{"radius", "0.05", "curl radius in head radii"},
                            {"frequency", "5", "curl turns per unit of hair length"}})});
  c.push_back({"clustered", "hair grouped into tight clumps that converge to their tips",
               hairOptions("2000", "16", "1.5",
                           {{"clusters", "64", "number of clumps (<= strands)"},
                            {"spread", "0.1", "clump radius at the scalp in head radii"}})});
  {
    std::vector<OptionInfo> o = commonOptions(
        "20000", "6", "0.1", "fur length as a fraction of the base mesh's bounding radius");
    o[7].help = "mesh to grow fur on (.obj, .ply, .tfxmesh), drawn opaque (default: a unit sphere)";
    o.push_back({"droop", "0.5", "gravity bend of the fur (0 = straight along the normal)"});
    o.push_back({"density", "", "strands per unit of mesh area (replaces strands=)"});
    c.push_back({"fur", "fur grown along a mesh's normals", std::move(o)});
  }
  {
    std::vector<OptionInfo> o =
        commonOptions("3000", "16", "1", "length of the clump's strands (world units)");
    o.push_back({"radius", "0.15", "radius of the dense clump"});
    o.push_back({"offset", "0.45",
                 "distance of the stray strand from the clump's axis, towards "
                 "the default light"});
    c.push_back(
        {"stray",
         "one strand between the light and a dense clump (the occupancy-map paper, Fig. 5a)",
         std::move(o)});
  }
  {
    std::vector<OptionInfo> o = commonOptions("200", "16", "2", "strand length (world units)");
    o.push_back({"wiggle", "0.1", "zigzag amplitude in the plane (strands cross each other)"});
    c.push_back({"sheet",
                 "strands in the plane z = 0: lit along -z, every fragment of a light texel "
                 "is at one depth (a zero depth range)",
                 std::move(o)});
  }
  c.push_back({"file",
               "strands from a file (.hair, .tfx, .ply), optionally with a mesh",
               {{"path", "", "strand file (required): .hair, .tfx or .ply"},
                {"mesh", "", "mesh file drawn opaque (.obj, .ply, .tfxmesh)"},
                {"strands", "all", "keep this many strands, evenly spaced (default: all)"},
                {"points_per_strand", "",
                 "PLY without a 'strand' element (e.g. NeuralHaircut): strands of N "
                 "consecutive vertices, 2.." +
                     std::to_string(kMaxPointsPerStrand)},
                {"alpha", "1", "hair opacity in [0,1] for transparency"},
                {"shadow_alpha", "0.5", "per-fragment shadow opacity in [0,1]"},
                {"seed", "1", "seed of the generation rule (guides=, instances=)"},
                {"up", "auto",
                 "the file's up axis, turned to +y: auto (z for .hair, Yuksel's models are "
                 "z-up; y for .tfx, TressFX's; for .ply, which does not say, the axis "
                 "along which the roots lie above the tips, as hanging hair's do, else y), y, "
                 "z, -y or -z; the render JSON's scene.up and up_reason"},
                {"color", "file",
                 "strand colours: file (the file's own, where it has them) or R/G/B in [0,1] "
                 "for every strand (color=0.45/0.3/0.18)"}}});
  // Stiff cases for every scene: extreme scales and degenerate segments.
  for (SceneInfo& info : c) {
    info.options.push_back({"scale", "1", "uniform scale of the whole scene, 1e-6..1e6"});
    info.options.push_back(
        {"zero_segments", "0", "1: every point doubled (every other segment has zero length)"});
    // The groom (scenes/groom.h, docs/geometry.md): guides, the generation rule, a crowd.
    info.options.push_back({"guides", "0",
                            "every n-th strand is a guide and the strands are made from the "
                            "guides by the generation rule (docs/geometry.md); 0: no guides"});
    info.options.push_back({"spread", "0.5",
                            "guides=: how far a strand leans to a neighbouring "
                            "guide, 0..1"});
    info.options.push_back(
        {"offset", "0.5", "guides=: per-strand offset in mean guide spacings, 0..10"});
    info.options.push_back(
        {"noise", "0.1", "guides=: per-point noise at the tip in mean guide spacings, 0..10"});
    info.options.push_back({"clump", "0", "guides=: pull to the home guide at the tip, 0..1"});
    info.options.push_back({"lod", "1",
                            "guides=: level of detail, the share of the strands kept (0..1], "
                            "their thickness widened by 1/lod"});
    info.options.push_back({"instances", "1",
                            "copies of the groom in a grid on the floor, each turned and made "
                            "with its own seed, 1..10000"});
  }
  return c;
}

// ---------------------------------------------------------------- options

std::string shortest(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// OptionReader (shared with the techniques) plus what the generators need on top:
// exclusive lower bounds and errors prefixed with the scene.
class Options {
 public:
  Options(const Spec& spec, const SceneInfo& info)
      : reader_(spec, info.options, "scene '" + info.name + "'"), name_(info.name) {}

  bool given(const std::string& key) const { return reader_.has(key); }
  std::string text(const std::string& key) const { return reader_.text(key); }
  std::string choice(const std::string& key, const std::vector<std::string>& valid) const {
    return reader_.choice(key, valid);
  }
  int64_t integer(const std::string& key, int64_t lo, int64_t hi) const {
    return int64_t(reader_.integer(key, lo, hi));
  }
  // A finite number in [lo, hi] (or (lo, hi] when loExclusive).
  float real(const std::string& key, double lo, double hi, bool loExclusive = false) const {
    const double v = reader_.number(key, lo, hi);
    if (loExclusive && !(v > lo)) {
      throw error("option " + key + "=" + text(key) + " is out of range: must be greater than " +
                  shortest(lo));
    }
    return float(v);
  }
  InputError error(const std::string& what) const {
    return InputError("scene '" + name_ + "': " + what);
  }

 private:
  OptionReader reader_;
  std::string name_;
};

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

struct Common {
  int64_t strands = 0;
  int points = 0;
  uint32_t seed = 1;
  float length = 1.0f;
  float thickness = 0.005f;
};

void checkTotal(const Options& o, uint64_t strands, uint64_t points) {
  if (strands * points > kMaxTotalPoints) {
    throw o.error(std::to_string(strands) + " strands x " + std::to_string(points) +
                  " points = " + std::to_string(strands * points) +
                  " points exceeds the limit of " + std::to_string(kMaxTotalPoints));
  }
}

Common readCommon(const Options& o, Scene& scene, bool readStrands = true) {
  Common c;
  c.strands = readStrands ? o.integer("strands", 1, kMaxStrands) : 0;
  c.points = int(o.integer("points", 2, kMaxPointsPerStrand));
  c.seed = uint32_t(o.integer("seed", 0, std::numeric_limits<uint32_t>::max()));
  c.length = o.real("length", 0.0, 100.0, true);
  c.thickness = o.real("thickness", 0.0, 1000.0, true);
  scene.hairAlpha = o.real("alpha", 0.0, 1.0);
  scene.shadowAlpha = o.real("shadow_alpha", 0.0, 1.0);
  if (readStrands) checkTotal(o, uint64_t(c.strands), uint64_t(c.points));
  return c;
}

void addHeadOrMesh(const Options& o, Scene& scene) {
  const bool head = o.integer("head", 0, 1) == 1;
  const std::string mesh = o.text("mesh");
  if (!mesh.empty()) {
    scene.mesh = loadMesh(mesh);
  } else if (head) {
    scene.mesh = makeSphere(1.0f, 48, 24);
  }
}

int fineSegments(int points) { return std::max(128, 4 * (points - 1)); }

enum class HairStyle { Straight, Wavy, Curly };

Scene makeHair(const Options& o, HairStyle style) {
  Scene scene;
  const Common c = readCommon(o, scene);
  float amplitude = 0, frequency = 0, radius = 0;
  if (style == HairStyle::Wavy) {
    amplitude = o.real("amplitude", 0.0, 10.0);
    frequency = o.real("frequency", 0.0, 1000.0);
  } else if (style == HairStyle::Curly) {
    radius = o.real("radius", 0.0, 10.0);
    frequency = o.real("frequency", 0.0, 1000.0);
  }
  addHeadOrMesh(o, scene);
  Rng rng(c.seed);
  const int M = fineSegments(c.points);
  reserve(scene.strands, std::size_t(c.strands), std::size_t(c.points));
  for (int64_t s = 0; s < c.strands; ++s) {
    const glm::vec3 root = sampleScalp(rng);
    const float length = c.length * rng.range(0.9f, 1.1f);
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
    appendStrand(scene.strands, fine, c.points, color, c.thickness);
  }
  return scene;
}

Scene makeClustered(const Options& o) {
  Scene scene;
  const Common c = readCommon(o, scene);
  const int64_t clusters = o.integer("clusters", 1, kMaxStrands);
  const float spread = o.real("spread", 0.0, 10.0);
  if (clusters > c.strands) {
    throw o.error("clusters=" + std::to_string(clusters) +
                  " exceeds strands=" + std::to_string(c.strands));
  }
  addHeadOrMesh(o, scene);
  Rng rng(c.seed);
  const int M = fineSegments(c.points);
  reserve(scene.strands, std::size_t(c.strands), std::size_t(c.points));
  for (int64_t k = 0; k < clusters; ++k) {
    const int64_t members = c.strands / clusters + (k < c.strands % clusters ? 1 : 0);
    const glm::vec3 root = sampleScalp(rng);
    const float length = c.length * rng.range(0.9f, 1.1f);
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
      appendStrand(scene.strands, fine, c.points, color, c.thickness);
    }
  }
  return scene;
}

// Occupancy maps paper, Fig. 5a: a dense clump of vertical strands and, in
// front of it as seen from the default light (fitLight's direction), a single
// stray strand whose shadow falls across the clump: a thin occluder far from
// the others, which layer-based techniques place badly.
Scene makeStray(const Options& o) {
  Scene scene;
  const Common c = readCommon(o, scene);
  const float radius = o.real("radius", 0.0, 100.0, true);
  const float offset = o.real("offset", 0.0, 100.0);
  if (!o.text("mesh").empty()) scene.mesh = loadMesh(o.text("mesh"));
  Rng rng(c.seed);
  reserve(scene.strands, std::size_t(c.strands) + 1, std::size_t(c.points));
  auto vertical = [&](glm::vec2 xz, const glm::vec3& color) {
    const std::vector<glm::vec3> line = {{xz.x, 0.5f * c.length, xz.y},
                                         {xz.x, -0.5f * c.length, xz.y}};
    appendStrand(scene.strands, line, c.points, color, c.thickness);
  };
  for (int64_t k = 0; k < c.strands; ++k) {
    const float r = radius * std::sqrt(rng.u());
    const float phi = rng.range(0.0f, 2.0f * kPi);
    vertical({r * std::cos(phi), r * std::sin(phi)}, strandColor(rng, scene.hairColor));
  }
  // Towards the light: against fitLight()'s direction, in the horizontal plane.
  const glm::vec2 towardLight = glm::normalize(glm::vec2(1.0f, 0.8f));
  vertical(offset * towardLight, scene.hairColor);
  return scene;
}

Scene makeSheet(const Options& o) {
  Scene scene;
  const Common c = readCommon(o, scene);
  const float wiggle = o.real("wiggle", 0.0, 100.0);
  if (!o.text("mesh").empty()) scene.mesh = loadMesh(o.text("mesh"));
  Rng rng(c.seed);
  reserve(scene.strands, std::size_t(c.strands), std::size_t(c.points));
  for (int64_t k = 0; k < c.strands; ++k) {
    const float x = c.strands > 1 ? -1.0f + 2.0f * float(k) / float(c.strands - 1) : 0.0f;
    std::vector<glm::vec3> zigzag;
    for (int i = 0; i < c.points; ++i) {
      const float t = float(i) / float(c.points - 1);
      const float side = (i % 2 ? 1.0f : -1.0f) * wiggle;
      zigzag.push_back({x + side, 0.5f * c.length - t * c.length, 0.0f});
    }
    appendStrand(scene.strands, zigzag, c.points, strandColor(rng, scene.hairColor), c.thickness);
  }
  return scene;
}

// The stiff-case options every scene has: a uniform scale and doubled points.
void applyScaleAndZeroSegments(const Options& o, Scene& scene) {
  const float scale = o.real("scale", 1e-6, 1e6);
  if (scale != 1.0f) {
    for (auto& p : scene.strands.points) p *= scale;
    for (auto& t : scene.strands.thickness) t *= scale;
    for (auto& p : scene.mesh.positions) p *= scale;
  }
  if (o.integer("zero_segments", 0, 1) == 0) return;
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

// guides= and instances=: the groom kept with the scene, its strands made by the
// rule on the CPU, and the mesh repeated with every instance.
void applyGroom(const Options& o, Scene& scene) {
  GroomSettings g;
  g.guideEvery = uint32_t(o.integer("guides", 0, kMaxStrands));
  g.instances = uint32_t(o.integer("instances", 1, 10000));
  g.seed = uint32_t(o.integer("seed", 0, std::numeric_limits<uint32_t>::max()));
  g.spread = o.real("spread", 0.0, 1.0);
  g.offset = o.real("offset", 0.0, 10.0);
  g.noise = o.real("noise", 0.0, 10.0);
  g.clump = o.real("clump", 0.0, 1.0);
  g.lod = o.real("lod", 0.0, 1.0, true);
  if (g.guideEvery == 0)
    for (const char* key : {"spread", "offset", "noise", "clump", "lod"})
      if (o.given(key))
        throw o.error(std::string(key) + "= needs guides= (every n-th strand a guide)");
  if (g.guideEvery == 0 && g.instances == 1) return;
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

Scene makeFur(const Options& o) {
  Scene scene;
  Common c = readCommon(o, scene, false);
  const float droop = o.real("droop", 0.0, 100.0);
  const bool useDensity = o.given("density");
  const float density = useDensity ? o.real("density", 0.0, 1e12, true) : 0.0f;
  if (useDensity && o.given("strands")) {
    throw o.error("give strands= (total) or density= (per unit area), not both");
  }
  if (!useDensity) c.strands = o.integer("strands", 1, kMaxStrands);
  const std::string meshPath = o.text("mesh");
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
      throw o.error("density=" + o.text("density") + " over an area of " + std::to_string(area) +
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

// "R/G/B", each in [0,1] (a spec's commas separate its options).
glm::vec3 colorOption(const Options& o, const std::string& key) {
  const std::string t = o.text(key);
  float c[3];
  std::size_t at = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t end = i < 2 ? t.find('/', at) : t.size();
    char* stop = nullptr;
    const std::string part = end == std::string::npos ? "" : t.substr(at, end - at);
    c[i] = std::strtof(part.c_str(), &stop);
    if (part.empty() || *stop != '\0' || !(c[i] >= 0.0f && c[i] <= 1.0f))
      throw o.error(key + "=" + t + ": expected file or R/G/B, three numbers in [0,1]");
    at = end + 1;
  }
  return {c[0], c[1], c[2]};
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

Scene makeFile(const Options& o) {
  Scene scene;
  const std::string path = o.text("path");
  if (path.empty()) throw o.error("path= is required (a .hair, .tfx or .ply strand file)");
  scene.hairAlpha = o.real("alpha", 0.0, 1.0);
  scene.shadowAlpha = o.real("shadow_alpha", 0.0, 1.0);
  int64_t keep = 0;  // 0 = all
  if (o.text("strands") != "all") keep = o.integer("strands", 1, kMaxStrands);
  uint32_t pointsPerStrand = 0;  // 0 = not given
  if (o.given("points_per_strand")) {
    pointsPerStrand = uint32_t(o.integer("points_per_strand", 2, kMaxPointsPerStrand));
  }
  std::string up = o.choice("up", {"auto", "y", "z", "-y", "-z"});
  std::optional<glm::vec3> color;
  if (o.text("color") != "file") color = colorOption(o, "color");
  scene.frameByBox = true;
  const std::string mesh = o.text("mesh");
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

}  // namespace

const std::vector<SceneInfo>& sceneCatalog() {
  static const std::vector<SceneInfo> catalog = buildCatalog();
  return catalog;
}

namespace {
// The generator or loader a spec names.
void buildScene(const Spec& spec, const Options& o, Scene& scene) {
  if (spec.name == "straight") {
    scene = makeHair(o, HairStyle::Straight);
  } else if (spec.name == "wavy") {
    scene = makeHair(o, HairStyle::Wavy);
  } else if (spec.name == "curly") {
    scene = makeHair(o, HairStyle::Curly);
  } else if (spec.name == "clustered") {
    scene = makeClustered(o);
  } else if (spec.name == "fur") {
    scene = makeFur(o);
  } else if (spec.name == "stray") {
    scene = makeStray(o);
  } else if (spec.name == "sheet") {
    scene = makeSheet(o);
  } else {
    scene = makeFile(o);
  }
}
}  // namespace

Scene makeScene(const Spec& spec) {
  const std::vector<SceneInfo>& catalog = sceneCatalog();
  const SceneInfo* info = nullptr;
  std::vector<std::string> names;
  for (const SceneInfo& s : catalog) {
    names.push_back(s.name);
    if (s.name == spec.name) info = &s;
  }
  if (!info) throw InputError(unknownNameMessage("scene", spec.name, names));
  const Options o(spec, *info);
  Scene scene;
  try {
    buildScene(spec, o, scene);
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

}  // namespace sb
