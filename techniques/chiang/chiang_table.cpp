#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <utility>

#include "pbr/hair_bsdf.h"
#include "techniques/chiang/chiang.h"

namespace sb {

namespace {

constexpr double kPi = std::numbers::pi;
// The colour's floor (pbr/strand_render.cpp clamps a strand's colour to [1e-3, 1]).
constexpr float kMinColor = 1e-3f;
// Steps of the h-average, midpoints in gamma_o = asin(h) (dh = cos(gamma_o) dgamma_o: dense
// where Phi(h) turns fastest, near the fibre's edges).
constexpr int kSteps = 256;

std::size_t at(int p, int x, int s, int phi) {
  return ((std::size_t(p) * SB_CHIANG_X + x) * SB_CHIANG_SIN + s) * SB_CHIANG_PHI + phi;
}

std::vector<float> build(float betaN, float eta) {
  pbr::HairParams hp;
  hp.betaN = betaN;
  hp.eta = eta;
  const double s = pbr::HairBsdf(hp).logisticScale();
  const double xMax = chiangXMax(betaN);
  std::vector<double> sum(
      std::size_t(SB_CHIANG_LOBES) * SB_CHIANG_X * SB_CHIANG_SIN * SB_CHIANG_PHI + SB_CHIANG_X);
  std::vector<double> np(std::size_t(3) * SB_CHIANG_PHI);
  for (int is = 0; is < SB_CHIANG_SIN; ++is) {
    // The grazing end is kept off 1, where theta_o's Bravais index is infinite.
    const double sinO = std::min(double(is) / (SB_CHIANG_SIN - 1), 0.9999);
    const double cosO = std::sqrt(1.0 - sinO * sinO);
    const double sinT = sinO / eta;
    const double cosT = std::sqrt(1.0 - sinT * sinT);
    const double etaP = std::sqrt(double(eta) * eta - sinO * sinO) / cosO;
    for (int ih = 0; ih < kSteps; ++ih) {
      const double gammaO = -kPi / 2 + (ih + 0.5) * kPi / kSteps;
      const double h = std::sin(gammaO);
      const double w = std::cos(gammaO) * (kPi / kSteps) / 2.0;  // the average over h in [-1, 1]
      const double sinGT = std::clamp(h / etaP, -1.0, 1.0);
      const double gammaT = std::asin(sinGT);
      const double cosGT = std::sqrt(1.0 - sinGT * sinGT);
      for (int p = 0; p < 3; ++p)
        for (int k = 0; k < SB_CHIANG_PHI; ++k)
          np[std::size_t(p) * SB_CHIANG_PHI + k] =
              pbr::hair::Np(kPi * k / (SB_CHIANG_PHI - 1), p, s, gammaO, gammaT);
      for (int ix = 0; ix < SB_CHIANG_X; ++ix) {
        const double x = xMax * ix / (SB_CHIANG_X - 1);
        const double t = std::exp(-x * x * 2.0 * cosGT / cosT);  // one crossing, as pbr's
        const auto ap = pbr::hair::Ap(cosO, eta, h, glm::dvec3(t));
        for (int p = 0; p < 3; ++p)
          for (int k = 0; k < SB_CHIANG_PHI; ++k)
            sum[at(p, ix, is, k)] += w * ap[p].x * np[std::size_t(p) * SB_CHIANG_PHI + k];
        // The higher orders, uniform in azimuth (pbr::HairBsdf's last term).
        for (int k = 0; k < SB_CHIANG_PHI; ++k) sum[at(3, ix, is, k)] += w * ap[3].x / (2 * kPi);
      }
    }
  }
  // chiangOpacity's row: the tracer's own mean transmittance, one definition for both.
  for (int ix = 0; ix < SB_CHIANG_X; ++ix) {
    const double x = xMax * ix / (SB_CHIANG_X - 1);
    sum[SB_CHIANG_OPACITY + std::size_t(ix)] =
        pbr::meanFibreTransmittance(glm::vec3(float(x * x)), eta, 0.0f).x;
  }
  return std::vector<float>(sum.begin(), sum.end());
}

}  // namespace

float chiangXMax(float betaN) {
  return std::sqrt(pbr::sigmaAFromReflectance(glm::vec3(kMinColor), betaN).x);
}

float chiangShadowAlpha(glm::vec3 color, float betaN, float eta) {
  // The tracer's own mean transmittance (pbr/hair_bsdf.h) at normal incidence: one definition
  // of the light a fibre lets through for the raster and the references.
  const glm::vec3 sigma = pbr::sigmaAFromReflectance(glm::clamp(color, kMinColor, 1.0f), betaN);
  const glm::vec3 t = pbr::meanFibreTransmittance(sigma, eta, 0.0f);
  return 1.0f - (0.2126f * t.r + 0.7152f * t.g + 0.0722f * t.b);
}

const std::vector<float>& chiangLobeTable(float betaN, float eta) {
  static std::mutex mutex;
  static std::map<std::pair<float, float>, std::vector<float>> tables;
  const std::lock_guard<std::mutex> lock(mutex);
  auto it = tables.find({betaN, eta});
  if (it == tables.end()) it = tables.emplace(std::pair{betaN, eta}, build(betaN, eta)).first;
  return it->second;
}

glm::vec3 chiangShade(const ChiangParams& p, const std::vector<float>& table, glm::vec3 T,
                      glm::vec3 L, glm::vec3 V, glm::vec3 color) {
  glsl::chiangTable = table.data();
  return glsl::chiang(T, L, V, color, p.chiangVariance, p.chiangTilt1, p.chiangTilt4);
}

}  // namespace sb
