// Guides, their neighbours, the crowd's placements, and the generation rule
// (groom_rule.h) run on the CPU. Built with -ffp-contract=off (CMakeLists.txt),
// as the rule's GLSL is SB_PRECISE: the same strands bit for bit.
#include "scenes/groom.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "base/errors.h"
#include "scenes/groom_rule.h"
#include "scenes/scene.h"
#include "scenes/view.h"

namespace sb {

namespace {

constexpr uint32_t kK = SB_GROOM_NEIGHBOURS;
// Neighbours are found by comparing every pair of roots: fine for guides.
constexpr uint32_t kMaxGuides = 20000;

// Strand s's point at parameter u in [0, 1] along its points (linear between them).
template <class T>
T resampled(const std::vector<T>& v, uint32_t first, uint32_t count, uint32_t j, uint32_t points) {
  if (count == points) return v[first + j];
  const double x = double(j) * double(count - 1) / double(points - 1);
  const uint32_t a = std::min(uint32_t(x), count - 2);
  const float t = float(x - a);
  return v[first + a] + (v[first + a + 1] - v[first + a]) * t;
}

void findNeighbours(Groom& g) {
  g.neighbours.assign(std::size_t(g.guideCount) * kK, 0);
  double spacing = 0;
  for (uint32_t a = 0; a < g.guideCount; ++a) {
    const glm::vec3 root(g.guidePoints[std::size_t(a) * g.points]);
    // The kK nearest other roots, ties to the lower index (deterministic).
    std::vector<std::pair<float, uint32_t>> best;
    for (uint32_t b = 0; b < g.guideCount; ++b) {
      if (b == a) continue;
      const glm::vec3 d = glm::vec3(g.guidePoints[std::size_t(b) * g.points]) - root;
      best.push_back({glm::dot(d, d), b});
      std::push_heap(best.begin(), best.end());
      if (best.size() > kK) {
        std::pop_heap(best.begin(), best.end());
        best.pop_back();
      }
    }
    std::sort_heap(best.begin(), best.end());
    for (uint32_t k = 0; k < kK; ++k)
      g.neighbours[std::size_t(a) * kK + k] =
          best.empty() ? a : best[std::min<std::size_t>(k, best.size() - 1)].second;
    if (!best.empty()) spacing += std::sqrt(double(best[0].first));
  }
  // The mean distance to the nearest guide: the rule's offset and noise scale.
  g.offset *= float(spacing / g.guideCount);
  g.noise *= float(spacing / g.guideCount);
}

}  // namespace

Groom makeGroom(const Strands& strands, const GroomSettings& s) {
  Groom g;
  std::vector<uint32_t> usable;  // strands of at least 2 points
  for (std::size_t k = 0; k < strands.strandCount(); ++k)
    if (strands.pointCount[k] >= 2) usable.push_back(uint32_t(k));
  if (usable.empty()) throw InputError("groom: no strand of 2 or more points to guide");
  std::vector<uint32_t> guides;
  const uint32_t every = std::max(s.guideEvery, 1u);
  for (std::size_t k = 0; k < usable.size(); k += every) guides.push_back(usable[k]);
  if (s.guideEvery > 0 && guides.size() > kMaxGuides)
    throw InputError("guides=" + std::to_string(s.guideEvery) + " keeps " +
                     std::to_string(guides.size()) + " guides, more than " +
                     std::to_string(kMaxGuides) + ": give a larger guides=");
  g.guideCount = uint32_t(guides.size());
  g.strands = uint32_t(usable.size());
  for (uint32_t k : guides) g.points = std::max(g.points, strands.pointCount[k]);
  g.guidePoints.reserve(std::size_t(g.guideCount) * g.points);
  g.guideColors.reserve(std::size_t(g.guideCount) * g.points);
  for (uint32_t k : guides) {
    const uint32_t first = strands.firstPoint[k], count = strands.pointCount[k];
    for (uint32_t j = 0; j < g.points; ++j) {
      g.guidePoints.push_back(glm::vec4(resampled(strands.points, first, count, j, g.points),
                                        resampled(strands.thickness, first, count, j, g.points)));
      g.guideColors.push_back(
          glm::vec4(resampled(strands.colors, first, count, j, g.points),
                    resampled(strands.transparency, first, count, j, g.points)));
    }
  }
  g.alongStep = 1.0f / float(g.points - 1);
  g.lod = s.lod;
  g.lodPixels = s.lodPixels;
  // The order a row cut short by the level of detail keeps its guides: by a hash
  // of the guide and the seed (integers: the same on every machine).
  std::vector<std::pair<uint32_t, uint32_t>> keyed(g.guideCount);
  for (uint32_t a = 0; a < g.guideCount; ++a)
    keyed[a] = {groom_rule::groomHash(a ^ groom_rule::groomHash(s.seed + 0x2545f491u)), a};
  std::sort(keyed.begin(), keyed.end());
  for (const auto& k : keyed) g.guideOrder.push_back(k.second);
  if (s.guideEvery > 0) {
    g.spread = s.spread;
    g.offset = s.offset;
    g.noise = s.noise;
    g.clump = s.clump;
    findNeighbours(g);
  } else {
    // Every strand its own guide, made as it is: the neighbours are never weighed.
    g.neighbours.resize(std::size_t(g.guideCount) * kK);
    for (uint32_t a = 0; a < g.guideCount; ++a)
      for (uint32_t k = 0; k < kK; ++k) g.neighbours[std::size_t(a) * kK + k] = a;
  }

  // The crowd: a square grid in the floor plane, each instance turned about +y
  // around the groom's centre by an angle of its seed (one instance stays as it is).
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::vec3& p : strands.points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::vec3 centre = 0.5f * (lo + hi);
  const float extent = std::max({hi.x - lo.x, hi.z - lo.z, hi.y - lo.y, 1e-6f});
  g.centre = centre;
  g.radius = 0.5f * glm::length(hi - lo);
  const float spacing = 1.25f * extent;
  const uint32_t n = s.instances;
  const uint32_t cols = uint32_t(std::ceil(std::sqrt(double(n))));
  const uint32_t rows = (n + cols - 1) / cols;
  for (uint32_t k = 0; k < n; ++k) {
    const uint32_t seed = groom_rule::groomHash(s.seed ^ groom_rule::groomHash(k + 0x632be5abu));
    g.instanceSeeds.push_back(seed);
    if (n == 1) {
      g.placements.push_back({1.0f, 0.0f, 0.0f, 0.0f});
      continue;
    }
    const float angle = 2.0f * std::numbers::pi_v<float> * groom_rule::groomUnit(seed);
    const float c = std::cos(angle), sn = std::sin(angle);
    const float gx = (float(k % cols) - 0.5f * float(cols - 1)) * spacing;
    const float gz = (float(k / cols) - 0.5f * float(rows - 1)) * spacing;
    // groomPlace(p) = R p + t; R (p - centre) + centre + grid = R p + (centre - R centre + grid).
    g.placements.push_back({c, sn, centre.x - (c * centre.x - sn * centre.z) + gx,
                            centre.z - (sn * centre.x + c * centre.z) + gz});
  }
  for (uint32_t k = 0; k < n; ++k) g.lods.push_back({k * g.strands, g.strands, 1.0f, 0});
  return g;
}

void groomLevelOfDetail(Groom& g, const Camera& camera, uint32_t imageHeight) {
  // Pixels across the image's height per world unit at distance 1.
  const double focal =
      0.5 * imageHeight / std::tan(0.5 * double(camera.fovYDegrees) * std::numbers::pi / 180.0);
  uint32_t first = 0;
  for (uint32_t k = 0; k < g.instanceCount(); ++k) {
    double share = 1;
    if (g.lod < 1.0f) share = g.lod;
    if (g.lodPixels > 0) {
      // The placement turns an instance about its centre: its sphere moves with the grid.
      const glm::vec3 c = groom_rule::groomPlace(g.centre, g.placements[k]);
      const double d = glm::length(c - camera.eye);
      const double pixels = d > g.radius ? 2.0 * g.radius * focal / d : 1e30;
      share = std::min(1.0, (pixels / g.lodPixels) * (pixels / g.lodPixels));
    }
    const uint32_t kept = std::clamp(uint32_t(std::lround(share * g.strands)), 1u, g.strands);
    g.lods[k] = {first, kept, float(double(g.strands) / double(kept)), 0};
    first += kept;
  }
}

Strands generateStrands(const Groom& g) {
  using namespace groom_rule;
  Strands out;
  const std::size_t total = std::size_t(g.totalPoints());
  out.points.resize(total);
  out.colors.resize(total);
  out.thickness.resize(total);
  out.transparency.resize(total);
  out.firstPoint.resize(std::size_t(g.totalStrands()));
  out.pointCount.assign(std::size_t(g.totalStrands()), g.points);
  for (uint32_t k = 0; k < g.instanceCount(); ++k) {
    const GroomInstanceLod lod = g.lods[k];
    const uint32_t row = groomLodCutRow(lod.kept, g.strands, g.guideCount);
    for (uint32_t t = 0; t < lod.kept; ++t) {
      const uint32_t i = t < row ? t : row + g.guideOrder[t - row];
      const std::size_t strand = std::size_t(lod.first) + t;
      const uint32_t seed = groomStrandSeed(g.instanceSeeds[k], i);
      const uint32_t home = i % g.guideCount;
      const uint32_t other =
          g.neighbours[std::size_t(home) * SB_GROOM_NEIGHBOURS + groomNeighbourSlot(seed)];
      const float w = groomWeight(seed, g.spread);
      const glm::vec3 offset = groomJitter(seed, g.offset);
      out.firstPoint[strand] = uint32_t(strand * g.points);
      for (uint32_t j = 0; j < g.points; ++j) {
        const glm::vec4 h = g.guidePoints[std::size_t(home) * g.points + j];
        const glm::vec4 o = g.guidePoints[std::size_t(other) * g.points + j];
        const glm::vec3 noise = groomJitter(groomPointSeed(seed, j), g.noise);
        const glm::vec3 p = groomPoint(glm::vec3(h), glm::vec3(o), w, offset, g.clump,
                                       float(j) * g.alongStep, noise);
        const std::size_t at = strand * g.points + j;
        const glm::vec4 c = g.guideColors[std::size_t(home) * g.points + j];
        out.points[at] = groomPlace(p, g.placements[k]);
        out.thickness[at] = groomThickness(h.w, lod.widen);
        out.colors[at] = glm::vec3(c);
        out.transparency[at] = c.w;
      }
    }
  }
  return out;
}

}  // namespace sb
