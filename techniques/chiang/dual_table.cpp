#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>

#include "techniques/chiang/dual.h"

namespace sb {

namespace {

constexpr double kPi = std::numbers::pi;
// Steps of the azimuthal integrals over the table's 64 samples (linear between them).
constexpr int kHalfSteps = 1024;
constexpr int kSpreadSteps = 128;
// 1 - a_f^2 is kept above this: the paper's series diverge for a fibre that absorbs nothing.
constexpr double kMinOneMinusAf2 = 1e-3;

std::size_t lobeAt(int p, int x, int s) {
  return ((std::size_t(p) * SB_CHIANG_X + x) * SB_CHIANG_SIN + s) * SB_CHIANG_PHI;
}

// Lobe row's value at azimuth phi in [-2 pi, 2 pi] (the row is even and 2 pi periodic),
// linear between the samples.
double rowAt(const float* row, double phi) {
  phi = std::abs(phi);
  if (phi > kPi) phi = 2 * kPi - phi;
  const double f = std::clamp(phi / kPi, 0.0, 1.0) * (SB_CHIANG_PHI - 1);
  const int i = std::min(int(f), SB_CHIANG_PHI - 2);
  const double t = f - i;
  return (1 - t) * row[i] + t * row[i + 1];
}

// 2 x the integral of the row over [a, b] in [0, pi] (the row is even in phi).
double halfIntegral(const float* row, double a, double b) {
  double sum = 0;
  for (int i = 0; i < kHalfSteps; ++i) sum += rowAt(row, a + (i + 0.5) * (b - a) / kHalfSteps);
  return 2 * sum * (b - a) / kHalfSteps;
}

// The lobes' centres in u = theta_i + theta_o: chiang.glsl tilts theta_o by +2 alpha (R),
// -alpha (TT), -4 alpha (TRT), so each peaks at u = -2 alpha, alpha, 4 alpha; the higher
// orders are not tilted.
std::array<double, SB_CHIANG_LOBES> lobeShifts(const ChiangParams& p) {
  const double a = std::asin(double(p.chiangTilt1.x));
  return {-2 * a, a, 4 * a, 0.0};
}

// What the table depends on: the fibre (its table's parameters, variances and tilt) and d_b.
using Key = std::array<float, 8>;

Key keyOf(const ChiangParams& p) {
  const glm::vec4 v = p.chiangVariance;
  return {p.chiangBetaN, p.chiangEta, v[0], v[1], v[2], v[3], p.chiangTilt1.x, p.chiangDensityB};
}

DualTerms terms(const ChiangParams& m, const std::vector<float>& lobes, int x, int s) {
  const auto shift = lobeShifts(m);
  DualTerms t;
  double wf = 0, wb = 0;
  for (int p = 0; p < SB_CHIANG_LOBES; ++p) {
    const float* row = lobes.data() + lobeAt(p, x, s);
    const double f = halfIntegral(row, kPi / 2, kPi);
    const double b = halfIntegral(row, 0, kPi / 2);
    const double width = std::sqrt(double(m.chiangVariance[p]));
    t.af += f;
    t.ab += b;
    t.alphaF += f * shift[p];
    t.alphaB += b * shift[p];
    t.betaF += f * width;
    t.betaB += b * width;
    wf += f;
    wb += b;
  }
  // The lobe-weighted means (the paper's eq. 12); a side that receives nothing keeps 0.
  if (wf > 0) t.alphaF /= wf, t.betaF /= wf;
  if (wb > 0) t.alphaB /= wb, t.betaB /= wb;
  // The neighbourhood's back-scattering (the paper's eqs. 13-17, one and three backward
  // scatterings between any number of forward ones).
  const double af2 = t.af * t.af, ab = t.ab, ab2 = ab * ab, ab3 = ab2 * ab;
  const double q = std::max(1.0 - af2, kMinOneMinusAf2);
  t.Ab = ab * af2 / q + ab3 * af2 / (q * q * q);
  t.deltaB =
      t.alphaB * (1 - 2 * ab2 / (q * q)) + t.alphaF * (2 * q * q + 4 * af2 * ab2) / (q * q * q);
  const double bf2 = t.betaF * t.betaF, bb2 = t.betaB * t.betaB;
  const double den = ab + ab3 * (2 * t.betaF + 3 * t.betaB);
  const double sigmaB =
      den > 0 ? (1 + m.chiangDensityB * af2) *
                    (ab * std::sqrt(2 * bf2 + bb2) + ab3 * std::sqrt(2 * bf2 + 3 * bb2)) / den
              : 0.0;
  t.sigmaB2 = sigmaB * sigmaB;
  return t;
}

std::vector<float> build(const ChiangParams& m) {
  const std::vector<float>& lobes = chiangLobeTable(m.chiangBetaN, m.chiangEta);
  std::vector<float> out(SB_DUAL_TABLE_SIZE, 0.0f);
  std::copy(lobes.begin(), lobes.begin() + SB_DUAL_LOBES, out.begin());
  std::copy(lobes.begin() + SB_CHIANG_OPACITY, lobes.begin() + SB_CHIANG_OPACITY + SB_CHIANG_X,
            out.begin() + SB_DUAL_OPACITY);
  // N^G_p: each lobe seen by light whose azimuth is spread uniformly over the forward half
  // circle (the paper's s_f = 1/pi there).
  for (int p = 0; p < SB_CHIANG_LOBES; ++p)
    for (int x = 0; x < SB_CHIANG_X; ++x)
      for (int s = 0; s < SB_CHIANG_SIN; ++s) {
        const float* row = lobes.data() + lobeAt(p, x, s);
        float* spread = out.data() + lobeAt(p + SB_CHIANG_LOBES, x, s);
        for (int k = 0; k < SB_CHIANG_PHI; ++k) {
          const double phi = kPi * k / (SB_CHIANG_PHI - 1);
          double sum = 0;
          for (int i = 0; i < kSpreadSteps; ++i)
            sum += rowAt(row, phi - (kPi / 2 + (i + 0.5) * kPi / kSpreadSteps));
          spread[k] = float(sum / kSpreadSteps);
        }
      }
  for (int x = 0; x < SB_CHIANG_X; ++x)
    for (int s = 0; s < SB_CHIANG_SIN; ++s) {
      const DualTerms t = terms(m, lobes, x, s);
      float* f = out.data() + SB_DUAL_PARAMS + (x * SB_CHIANG_SIN + s) * SB_DUAL_FIELDS;
      const float fields[SB_DUAL_FIELDS] = {float(t.af),
                                            float(t.betaF * t.betaF),
                                            float(t.Ab),
                                            float(std::sin(t.deltaB)),
                                            float(std::cos(t.deltaB)),
                                            float(t.sigmaB2)};
      std::copy(fields, fields + SB_DUAL_FIELDS, f);
    }
  return out;
}

}  // namespace

DualTerms dualTerms(const ChiangParams& p, int x, int sinTheta) {
  return terms(p, chiangLobeTable(p.chiangBetaN, p.chiangEta), x, sinTheta);
}

const std::vector<float>& dualTable(const ChiangParams& m) {
  static std::mutex mutex;
  static std::map<Key, std::vector<float>> tables;
  const std::lock_guard<std::mutex> lock(mutex);
  auto it = tables.find(keyOf(m));
  if (it == tables.end()) it = tables.emplace(keyOf(m), build(m)).first;
  return it->second;
}

glm::vec3 dualShade(const ChiangParams& p, glm::vec3 T, glm::vec3 L, glm::vec3 V, glm::vec3 color,
                    float visibility, float strandAlpha) {
  glsl::chiangTable = dualTable(p).data();
  return glsl::chiangDual(T, L, V, color, p.chiangVariance, p.chiangTilt1, p.chiangTilt4,
                          glm::vec2(p.chiangDensityF, p.chiangDensityB), visibility, strandAlpha);
}

}  // namespace sb
