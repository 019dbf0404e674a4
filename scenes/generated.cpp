// The generated scenes' shared options and geometry (scenes/generated.h).
#include "scenes/generated.h"

#include <algorithm>
#include <cmath>

#include "scenes/mesh_loaders.h"

namespace sb {

std::vector<Option<GeneratedScene>> generatedOptions(long long strands, long long points,
                                                     const char* length, const char* lengthHelp,
                                                     const char* meshHelp) {
  using GS = GeneratedScene;
  return opt::group<GS>(
      {opt::integer(&GS::strands, "strands", strands, 1, kMaxStrands, "number of strands"),
       opt::integer(&GS::points, "points", points, 2, kMaxPointsPerStrand,
                    "points per strand (>= 2)"),
       opt::inherited<GS>(seedOption("random seed (same seed, same scene)")),
       scene_opt::positive(&GS::length, "length", length, 100.0, lengthHelp),
       scene_opt::positive(&GS::thickness, "thickness", "0.005", 1000.0,
                           "strand thickness in world units"),
       opt::inherited<GS>(alphaOptions()),
       opt::inherited<GS>(opt::text(&SceneBase::mesh, "mesh", "", meshHelp))});
}

std::vector<Option<GeneratedScene>> hairOptions(long long strands, long long points,
                                                const char* length) {
  return opt::group<GeneratedScene>(
      {generatedOptions(strands, points, length, "hair length in head radii (head radius is 1)",
                        kMeshHelp),
       scene_opt::zeroOne(&GeneratedScene::head, "head", true,
                          "1: draw the spherical head as the opaque mesh; 0: no head")});
}

void checkGenerated(const GeneratedScene& o) {
  checkTotal(o, uint64_t(o.strands), uint64_t(o.points));
}

void addHeadOrMesh(const GeneratedScene& o, Scene& scene) {
  if (!o.mesh.empty()) {
    scene.mesh = loadMesh(o.mesh);
  } else if (o.head) {
    scene.mesh = makeSphere(1.0f, 48, 24);
  }
}

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

void basis(const glm::vec3& n, glm::vec3& t1, glm::vec3& t2) {
  const glm::vec3 a = std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  t1 = glm::normalize(glm::cross(n, a));
  t2 = glm::cross(n, t1);
}

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

}  // namespace sb
