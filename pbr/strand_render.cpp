#include "pbr/strand_render.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>
#include <thread>

#include "pbr/hair_bsdf.h"

namespace sb::pbr {

namespace {

constexpr float kPi = 3.14159265358979f;

// A sample's random numbers: PCG32 seeded from (seed, pixel, sample), so an image is the same
// whatever the threads and however its samples are split into passes.
class Rng {
 public:
  Rng(uint64_t seed, uint64_t pixel, uint64_t sample) {
    state_ = mix(seed ^ mix(pixel * 0x9E3779B97F4A7C15ull + sample));
    inc_ = (mix(pixel + 0x632BE59BD9B4E019ull * (sample + 1)) << 1u) | 1u;
    next();
  }
  float uniform() { return float(next() >> 8) * (1.0f / 16777216.0f); }
  glm::vec2 uniform2() {
    const float a = uniform();
    return {a, uniform()};
  }

 private:
  static uint64_t mix(uint64_t z) {  // splitmix64's finalizer
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  uint32_t next() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  uint64_t state_ = 0, inc_ = 1;
};

// Sample k's position in pixel i: the R2 sequence (Roberts 2018, the plastic number's
// additive recurrence), whose every prefix is spread evenly over the pixel, shifted by a
// random offset per pixel (Cranley-Patterson rotation) so pixels do not share a pattern. Any
// number of samples is stratified, so rendering can stop at a noise target. The standard
// error, computed as if samples were independent, then overstates the noise: conservative.
glm::vec2 pixelSample(uint64_t seed, uint64_t pixel, uint32_t k) {
  Rng shift(seed, pixel, ~0ull);
  const glm::vec2 base = shift.uniform2();
  const double a1 = 0.7548776662466927, a2 = 0.5698402909980532;  // 1/g, 1/g^2
  const double x = double(base.x) + a1 * double(k), y = double(base.y) + a2 * double(k);
  constexpr float kBelowOne = 0.99999994f;  // the float rounding of a fraction may reach 1
  return {std::min(float(x - std::floor(x)), kBelowOne),
          std::min(float(y - std::floor(y)), kBelowOne)};
}

glm::vec3 ndcOf(const glm::mat4& m, glm::vec3 p, bool& inside) {
  const glm::vec4 c = m * glm::vec4(p, 1.0f);
  const glm::vec3 ndc = glm::vec3(c) / c.w;
  inside = c.w > 0 && ndc.x >= -1 && ndc.x <= 1 && ndc.y >= -1 && ndc.y <= 1 && ndc.z <= 1;
  return ndc;
}

glm::vec3 toLight(const TraceLight& l, glm::vec3 p, float& distance) {
  if (!l.point) {
    distance = std::numeric_limits<float>::infinity();
    return l.toLight;
  }
  const glm::vec3 d = l.position - p;
  distance = glm::length(d);
  return distance > 0 ? d / distance : glm::vec3(0, 1, 0);
}

struct Lerped {
  glm::vec3 axis, color;
  float alpha;
};
Lerped lerpHit(const StrandScene& s, const StrandTracer& t, const StrandHit& h) {
  const uint32_t a = t.segmentStart()[h.segment];
  const std::vector<glm::vec3>& p = t.geometry().points;
  return {glm::mix(p[a], p[a + 1], h.u), glm::mix(s.colors[a], s.colors[a + 1], h.u),
          glm::mix(s.alpha[a], s.alpha[a + 1], h.u)};
}

glm::vec3 meshNormal(const StrandScene& s, const StrandTracer& t, uint32_t triangle, glm::vec3 p) {
  const TraceGeometry& g = t.geometry();
  const uint32_t i0 = g.meshIndices[3 * triangle], i1 = g.meshIndices[3 * triangle + 1],
                 i2 = g.meshIndices[3 * triangle + 2];
  const glm::vec3 a = g.meshPositions[i0], b = g.meshPositions[i1], c = g.meshPositions[i2];
  const glm::vec3 face = glm::cross(b - a, c - a);
  if (s.meshNormals.size() != g.meshPositions.size())
    return glm::dot(face, face) > 0 ? glm::normalize(face) : glm::vec3(0, 1, 0);
  // Barycentric weights of p, for the interpolated (smooth) normal the raster shades with.
  const float area = glm::dot(face, face);
  if (area <= 0) return glm::vec3(0, 1, 0);
  const float w1 = glm::dot(glm::cross(p - a, c - a), face) / area;
  const float w2 = glm::dot(glm::cross(b - a, p - a), face) / area;
  const glm::vec3 n =
      (1 - w1 - w2) * s.meshNormals[i0] + w1 * s.meshNormals[i1] + w2 * s.meshNormals[i2];
  return glm::dot(n, n) > 0 ? glm::normalize(n) : glm::normalize(face);
}

// A ray leaving a surface starts this far along (relative to the scene's size), so it does not
// find the surface it left.
float epsilonOf(const StrandTracer& t) {
  float r = 0;
  for (const glm::vec3& p : t.geometry().points)
    r = std::max({r, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  for (const glm::vec3& p : t.geometry().meshPositions)
    r = std::max({r, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  return std::max(r, 1.0f) * 1e-5f;
}

glm::vec3 primaryDirection(const StrandScene& s, float px, float py) {
  const float nx = 2.0f * px / float(s.width) - 1.0f;
  // Image row 0 at the top: ndc y = +1 there (the projection has no y flip).
  const float ny = 1.0f - 2.0f * py / float(s.height);
  const glm::vec4 far = s.invViewProj * glm::vec4(nx, ny, 1.0f, 1.0f);
  return glm::normalize(glm::vec3(far) / far.w - s.eye);
}

// Transmittance mode: one sample through (px, py).
glm::vec3 transmittanceSample(const StrandScene& s, const StrandTracer& eye,
                              const std::vector<const StrandTracer*>& light, const ShadeFn& shade,
                              float px, float py) {
  const glm::vec3 dir = primaryDirection(s, px, py);
  const RayHits hits = eye.trace(s.eye, dir, 0.0f, std::numeric_limits<float>::infinity());
  glm::vec3 color(0.0f);
  float through = 1.0f;
  std::vector<float> vis(s.lights.size());
  auto visibilities = [&](glm::vec3 p) {
    for (std::size_t l = 0; l < s.lights.size(); ++l)
      vis[l] = lightTransmittance(s, *light[std::min(l, light.size() - 1)], l, p);
  };
  for (const StrandHit& h : hits.strands) {
    const Lerped a = lerpHit(s, eye, h);
    visibilities(a.axis);
    const glm::vec3 c = shade({false, a.axis, h.tangent, a.color}, vis);
    color += through * a.alpha * c;
    through *= 1.0f - a.alpha;
    if (through <= 0) return color;
  }
  if (hits.mesh) {
    const glm::vec3 p = s.eye + hits.meshT * dir;
    visibilities(p);
    return color +
           through * shade({true, p, meshNormal(s, eye, hits.triangle, p), glm::vec3(0)}, vis);
  }
  return color + through * s.background;
}

// A local frame for the hair BSDF: x the tangent, z the normal of the ribbon that faces the ray.
struct Frame {
  glm::vec3 x, y, z;
  glm::vec3 toLocal(glm::vec3 v) const { return {glm::dot(v, x), glm::dot(v, y), glm::dot(v, z)}; }
  glm::vec3 toWorld(glm::vec3 v) const { return v.x * x + v.y * y + v.z * z; }
};
Frame hairFrame(glm::vec3 tangent, glm::vec3 wo) {
  glm::vec3 z = wo - glm::dot(wo, tangent) * tangent;
  if (glm::dot(z, z) < 1e-12f) {  // looking along the fibre: any normal
    z = std::abs(tangent.x) < 0.9f ? glm::cross(tangent, glm::vec3(1, 0, 0))
                                   : glm::cross(tangent, glm::vec3(0, 1, 0));
  }
  z = glm::normalize(z);
  return {tangent, glm::cross(z, tangent), z};
}

// Cosine-weighted direction about n.
glm::vec3 cosineSample(glm::vec3 n, glm::vec2 u) {
  const float r = std::sqrt(u.x), phi = 2 * kPi * u.y;
  const glm::vec3 t = std::abs(n.x) < 0.9f ? glm::normalize(glm::cross(n, glm::vec3(1, 0, 0)))
                                           : glm::normalize(glm::cross(n, glm::vec3(0, 1, 0)));
  const glm::vec3 b = glm::cross(n, t);
  return r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0f, 1 - u.x)) * n;
}

// The nearest surface along a ray, skipping the strand it leaves: a ribbon faces every ray, so
// a ray leaving a strand nearly along it (a light above straight hair) would run inside that
// strand's ribbon for its whole length. A fibre shadowing itself (a curl bending back over
// its own root) is the case this leaves out (docs/physics-reference.md).
struct Nearest {
  bool hit = false, mesh = false;
  float t = 0;
  StrandHit strand;
  uint32_t triangle = 0;
};
struct Skip {
  int64_t strand = -1;
};
Nearest nearest(const StrandTracer& t, glm::vec3 o, glm::vec3 d, float tnear, float tfar,
                Skip skip) {
  const RayHits h = t.trace(o, d, tnear, tfar);
  for (const StrandHit& s : h.strands)
    if (int64_t(t.segmentStrand()[s.segment]) != skip.strand) return {true, false, s.t, s, 0};
  if (h.mesh) return {true, true, h.meshT, {}, h.triangle};
  return {};
}

// The hair BSDF's parameters at a strand hit: absorption from the strand's colour.
glm::vec3 hitColor(const StrandScene& s, const StrandTracer& tr, const StrandHit& h) {
  const uint32_t a = tr.segmentStart()[h.segment];
  return glm::clamp(glm::mix(s.colors[a], s.colors[a + 1], h.u), 1e-3f, 1.0f);
}
HairParams hairParams(const StrandScene& s, const StrandTracer& tr, const StrandHit& h,
                      const RenderOptions& o) {
  HairParams hp;
  hp.h = h.h;
  hp.betaM = o.betaM;
  hp.betaN = o.betaN;
  hp.alphaDeg = o.alphaDeg;
  hp.eta = o.eta;
  hp.sigmaA = sigmaAFromReflectance(hitColor(s, tr, h), o.betaN);
  return hp;
}

// What a ray keeps through the strand it crosses at h (single mode's attenuation).
glm::vec3 throughFibre(const StrandScene& s, const StrandTracer& tr, const StrandHit& h,
                       const RenderOptions& o, glm::vec3 dir) {
  return fibreTransmittance(sigmaAFromReflectance(hitColor(s, tr, h), o.betaN), o.eta, h.h,
                            glm::dot(dir, h.tangent));
}

// Single mode: the light reaching p from a light at distance dist along wi, through every
// fibre on the way but the one p is on (its own crossing is the BSDF's); the mesh stops it.
glm::vec3 attenuatedVisibility(const StrandScene& s, const StrandTracer& tr, const RenderOptions& o,
                               glm::vec3 p, glm::vec3 wi, float dist, float eps,
                               int64_t skipStrand) {
  const RayHits h = tr.trace(p, wi, eps, dist);
  if (h.mesh) return glm::vec3(0.0f);
  glm::vec3 t(1.0f);
  for (const StrandHit& sh : h.strands)
    if (int64_t(tr.segmentStrand()[sh.segment]) != skipStrand) t *= throughFibre(s, tr, sh, o, wi);
  return t;
}

glm::vec3 lambertMesh(const StrandScene& s, const StrandTracer& tr, uint32_t triangle, glm::vec3 p,
                      glm::vec3 wo, glm::vec3& nrm) {
  nrm = meshNormal(s, tr, triangle, p);
  if (glm::dot(nrm, wo) < 0) nrm = -nrm;  // two-sided, as the raster shades it
  return s.meshAlbedo / kPi;
}

// Single mode: one camera ray through (px, py). Every fibre it crosses is lit directly (the
// hair BSDF, each light seen through attenuatedVisibility) and passes on what
// fibreTransmittance lets through, to the fibres, mesh or background behind: single
// scattering with fibres that attenuate, the rung the raster's Chiang model with exact
// visibility and world-width strands is compared with (docs/physics-reference.md).
glm::vec3 singleSample(const StrandScene& s, const StrandTracer& tr, const RenderOptions& o,
                       float eps, float px, float py) {
  const glm::vec3 dir = primaryDirection(s, px, py), wo = -dir;
  const RayHits hits = tr.trace(s.eye, dir, 0.0f, std::numeric_limits<float>::infinity());
  glm::vec3 color(0.0f), through(1.0f);
  for (const StrandHit& h : hits.strands) {
    const glm::vec3 p = s.eye + h.t * dir;
    const HairBsdf bsdf(hairParams(s, tr, h, o));
    const Frame fr = hairFrame(h.tangent, wo);
    const glm::vec3 woL = fr.toLocal(wo);
    const int64_t strand = int64_t(tr.segmentStrand()[h.segment]);
    for (const TraceLight& l : s.lights) {
      float dist = 0;
      const glm::vec3 wi = toLight(l, p, dist);
      const glm::vec3 f = bsdf.fCos(woL, fr.toLocal(wi));
      if (f.r + f.g + f.b <= 0) continue;
      color +=
          through * f * (kPi * l.color) * attenuatedVisibility(s, tr, o, p, wi, dist, eps, strand);
    }
    through *= throughFibre(s, tr, h, o, dir);
    if (std::max({through.r, through.g, through.b}) < 1e-6f) return color;
  }
  if (hits.mesh) {
    const glm::vec3 p = s.eye + hits.meshT * dir;
    glm::vec3 nrm;
    const glm::vec3 brdf = lambertMesh(s, tr, hits.triangle, p, wo, nrm);
    for (const TraceLight& l : s.lights) {
      float dist = 0;
      const glm::vec3 wi = toLight(l, p, dist);
      const float c = std::max(0.0f, glm::dot(nrm, wi));
      if (c > 0)
        color += through * brdf * c * (kPi * l.color) *
                 attenuatedVisibility(s, tr, o, p, wi, dist, eps, -1);
    }
    return color;
  }
  return color + through * s.background;
}

// Path mode: one path through (px, py).
glm::vec3 pathSample(const StrandScene& s, const StrandTracer& tr, const RenderOptions& o,
                     float eps, Rng& rng, float px, float py) {
  glm::vec3 origin = s.eye, dir = primaryDirection(s, px, py), throughput(1.0f), radiance(0.0f);
  Skip skip;
  for (uint32_t bounce = 0; bounce < o.bounces; ++bounce) {
    const Nearest n = nearest(tr, origin, dir, bounce == 0 ? 0.0f : eps,
                              std::numeric_limits<float>::infinity(), skip);
    if (!n.hit) {
      if (bounce == 0) radiance += s.background;
      break;
    }
    const glm::vec3 p = origin + n.t * dir, wo = -dir;
    skip = n.mesh ? Skip{} : Skip{int64_t(tr.segmentStrand()[n.strand.segment])};
    auto lit = [&](const TraceLight& l, const std::function<glm::vec3(glm::vec3)>& fCos) {
      float dist = 0;
      const glm::vec3 wi = toLight(l, p, dist);
      const glm::vec3 f = fCos(wi);
      if (f.r + f.g + f.b <= 0) return;
      if (nearest(tr, p, wi, eps, dist, skip).hit) return;
      // No falloff for a point light either: the raster shading has none (the light's colour
      // is the irradiance over pi wherever it arrives).
      radiance += throughput * f * (kPi * l.color);
    };
    if (n.mesh) {
      glm::vec3 nrm;
      const glm::vec3 brdf = lambertMesh(s, tr, n.triangle, p, wo, nrm);
      for (const TraceLight& l : s.lights)
        lit(l, [&](glm::vec3 wi) { return brdf * std::max(0.0f, glm::dot(nrm, wi)); });
      dir = cosineSample(nrm, rng.uniform2());
      throughput *= s.meshAlbedo;
    } else {
      const HairBsdf bsdf(hairParams(s, tr, n.strand, o));
      const Frame fr = hairFrame(n.strand.tangent, wo);
      const glm::vec3 woL = fr.toLocal(wo);
      for (const TraceLight& l : s.lights)
        lit(l, [&](glm::vec3 wi) { return bsdf.fCos(woL, fr.toLocal(wi)); });
      const glm::vec2 u0 = rng.uniform2(), u1 = rng.uniform2();
      const HairBsdf::Sample smp = bsdf.sample(woL, u0, u1);
      if (!(smp.pdf > 0)) break;
      dir = glm::normalize(fr.toWorld(smp.wi));
      throughput *= smp.weight;
    }
    origin = p;
    // Russian roulette past the third bounce: unbiased, it ends paths that carry little.
    if (bounce >= 3) {
      const float q = std::min(0.95f, std::max({throughput.r, throughput.g, throughput.b}));
      if (rng.uniform() >= q) break;
      throughput /= q;
    }
  }
  return radiance;
}

}  // namespace

double RenderImage::meanStderr() const {
  double sum = 0;
  for (float e : stderror) sum += e;
  return stderror.empty() ? 0.0 : sum / double(stderror.size());
}

double RenderImage::rmsStderr() const {
  double sum = 0;
  for (float e : stderror) sum += double(e) * e;
  return stderror.empty() ? 0.0 : std::sqrt(sum / double(stderror.size()));
}

glm::vec3 lightThroughFibres(const StrandScene& s, const StrandTracer& tracer,
                             const RenderOptions& o, glm::vec3 p, glm::vec3 wi, float dist,
                             int64_t skipStrand) {
  return attenuatedVisibility(s, tracer, o, p, wi, dist, epsilonOf(tracer), skipStrand);
}

float lightTransmittance(const StrandScene& s, const StrandTracer& tracer, std::size_t l,
                         glm::vec3 p) {
  const TraceLight& light = s.lights[l];
  bool inside = false;
  const glm::vec3 ndc = ndcOf(light.viewProj, p, inside);
  const float z = ndc.z - light.bias;
  if (!inside) return 1.0f;  // outside the light's frustum: lit, as the exact shadow has it
  if (light.texels > 0) {
    const glm::vec2 texel =
        glm::min(glm::floor((glm::vec2(ndc) + 1.0f) * 0.5f * float(light.texels)),
                 glm::vec2(float(light.texels - 1)));
    const glm::vec2 centre = (texel + 0.5f) / float(light.texels) * 2.0f - 1.0f;
    const glm::vec4 w = light.invViewProj * glm::vec4(centre, ndc.z, 1.0f);
    p = glm::vec3(w) / w.w;
  }
  float dist = 0;
  const glm::vec3 wi = toLight(light, p, dist);
  int n = 0;
  float tnear = 0;
  // A strand or the mesh counts where it is in front of p in the light's window depth by more
  // than the bias; a mesh hit that is not (p's own surface) lets the ray go on past it.
  for (int tries = 0; tries < 64; ++tries) {
    const RayHits h = tracer.trace(p, wi, tnear, dist);
    for (const StrandHit& sh : h.strands) {
      bool in = false;
      if (ndcOf(light.viewProj, p + sh.t * wi, in).z < z) ++n;
    }
    if (!h.mesh) break;
    bool in = false;
    if (ndcOf(light.viewProj, p + h.meshT * wi, in).z < z) return 0.0f;
    tnear = std::nextafter(h.meshT, std::numeric_limits<float>::infinity()) * 1.000001f;
  }
  return n == 0 ? 1.0f : std::pow(1.0f - s.shadowAlpha, float(n));
}

RenderImage renderStrands(const StrandScene& s, const StrandTracer& eye,
                          const std::vector<const StrandTracer*>& light, const RenderOptions& o,
                          const ShadeFn& shade,
                          const std::function<void(const std::string&)>& progress) {
  RenderImage img;
  img.width = s.width;
  img.height = s.height;
  const std::size_t pixels = std::size_t(s.width) * s.height;
  std::vector<glm::dvec3> sum(pixels, glm::dvec3(0)), sum2(pixels, glm::dvec3(0));
  const float eps = epsilonOf(eye);
  const uint32_t threads =
      o.threads ? o.threads : std::max(1u, std::thread::hardware_concurrency());
  const uint32_t spp = std::max(1u, o.spp);
  auto finish = [&](uint32_t n) {
    img.spp = n;
    img.mean.assign(pixels, glm::vec3(0));
    img.stderror.assign(pixels, 0.0f);
    for (std::size_t i = 0; i < pixels; ++i) {
      const glm::dvec3 m = sum[i] / double(n);
      img.mean[i] = glm::vec3(m);
      if (n > 1) {
        // The sample variance (n - 1), divided by n: the variance of the mean.
        const glm::dvec3 var =
            glm::max(sum2[i] / double(n) - m * m, glm::dvec3(0)) * (double(n) / (n - 1));
        img.stderror[i] = float(std::sqrt((var.x + var.y + var.z) / 3.0 / double(n)));
      }
    }
  };
  for (uint32_t k = 0; k < spp; ++k) {
    std::atomic<uint32_t> nextRow{0};
    auto work = [&] {
      for (uint32_t y = nextRow++; y < s.height; y = nextRow++)
        for (uint32_t x = 0; x < s.width; ++x) {
          const std::size_t i = std::size_t(y) * s.width + x;
          Rng rng(o.seed, i, k);
          // One sample: the pixel's centre; more: over the pixel (a box filter), stratified.
          const glm::vec2 j = spp == 1 ? glm::vec2(0.5f) : pixelSample(o.seed, i, k);
          const float px = float(x) + j.x, py = float(y) + j.y;
          glm::vec3 v;
          if (o.mode == Mode::Transmittance)
            v = transmittanceSample(s, eye, light, shade, px, py);
          else if (o.mode == Mode::Single)
            v = singleSample(s, eye, o, eps, px, py);
          else
            v = pathSample(s, eye, o, eps, rng, px, py);
          const glm::dvec3 d(std::isfinite(v.r + v.g + v.b) ? v : glm::vec3(0));
          sum[i] += d;
          sum2[i] += d * d;
        }
    };
    std::vector<std::thread> pool;
    for (uint32_t t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    const bool last = k + 1 == spp;
    if (o.noiseTarget > 0 || last || progress) finish(k + 1);
    std::ostringstream line;
    line << "pass " << (k + 1) << "/" << spp << ", noise " << img.rmsStderr();
    if (progress) progress(line.str());
    if (o.noiseTarget > 0 && k + 1 >= kMinSamplesForTarget && img.rmsStderr() < o.noiseTarget) {
      img.stoppedAtTarget = !last;
      break;
    }
  }
  return img;
}

}  // namespace sb::pbr
