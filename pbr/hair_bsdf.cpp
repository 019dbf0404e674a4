#include "pbr/hair_bsdf.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "base/errors.h"

namespace sb::pbr {

namespace {

constexpr double kPi = std::numbers::pi;

// Rec. 709 luminance: a lobe is drawn by its share of the scattered luminance (pbrt's y()).
double luminance(glm::dvec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

double safeSqrt(double x) { return std::sqrt(std::max(0.0, x)); }

std::string str(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

// Exit azimuth of lobe p for an ideal smooth cylinder (the paper's Phi).
double exitPhi(int p, double gammaO, double gammaT) {
  return 2.0 * p * gammaT - 2.0 * gammaO + p * kPi;
}

double logisticCdf(double x, double s) { return 1.0 / (1.0 + std::exp(-x / s)); }

}  // namespace

void checkHairParams(const HairParams& p) {
  auto fail = [](const std::string& what) { throw InputError("hair BSDF: " + what); };
  if (!(p.h >= -1.0f && p.h <= 1.0f)) fail("h " + str(p.h) + ": must be in [-1, 1]");
  // Below 1 the Bravais index sqrt(eta^2 - sin^2 theta_o) is not real.
  if (!(p.eta > 1.0f && std::isfinite(p.eta))) fail("eta " + str(p.eta) + ": must be above 1");
  for (int c = 0; c < 3; ++c)
    if (!(p.sigmaA[c] >= 0.0f && std::isfinite(p.sigmaA[c])))
      fail("sigma_a " + str(p.sigmaA[c]) + " (channel " + std::to_string(c) +
           "): must be finite and >= 0");
  // 0 would be a zero-variance lobe: a delta the BSDF cannot evaluate.
  if (!(p.betaM > 0.0f && p.betaM <= 1.0f)) fail("beta_m " + str(p.betaM) + ": must be in (0, 1]");
  if (!(p.betaN > 0.0f && p.betaN <= 1.0f)) fail("beta_n " + str(p.betaN) + ": must be in (0, 1]");
  if (!(std::abs(p.alphaDeg) < 90.0f))
    fail("alpha " + str(p.alphaDeg) + ": must be in (-90, 90) degrees");
}

glm::vec3 sigmaAFromConcentration(float eumelanin, float pheomelanin) {
  if (!(eumelanin >= 0.0f && std::isfinite(eumelanin) && pheomelanin >= 0.0f &&
        std::isfinite(pheomelanin)))
    throw InputError("melanin concentrations " + str(eumelanin) + ", " + str(pheomelanin) +
                     ": must be finite and >= 0");
  const glm::vec3 eu(0.419f, 0.697f, 1.37f);
  const glm::vec3 pheo(0.187f, 0.4f, 1.05f);
  return eumelanin * eu + pheomelanin * pheo;
}

glm::vec3 sigmaAFromReflectance(glm::vec3 color, float betaN) {
  if (!(betaN > 0.0f && betaN <= 1.0f))
    throw InputError("beta_n " + str(betaN) + ": must be in (0, 1]");
  const double b = betaN;
  const double denom = 5.969 - 0.215 * b + 2.532 * b * b - 10.73 * b * b * b +
                       5.574 * std::pow(b, 4) + 0.245 * std::pow(b, 5);
  glm::vec3 sigma;
  for (int c = 0; c < 3; ++c) {
    if (!(color[c] > 0.0f && color[c] <= 1.0f))
      throw InputError("color " + str(color[c]) + " (channel " + std::to_string(c) +
                       "): must be in (0, 1]");
    const double r = std::log(double(color[c])) / denom;
    sigma[c] = float(r * r);
  }
  return sigma;
}

glm::vec3 fibreTransmittance(glm::vec3 sigmaA, float eta, float h, float sinTheta) {
  const double s = std::clamp(double(sinTheta), -1.0, 1.0);
  const double hc = std::clamp(double(h), -1.0, 1.0);
  const glm::dvec3 t = hair::crossingTransmittance(s, eta, hc, glm::dvec3(sigmaA));
  return glm::vec3(hair::Ap(safeSqrt(1.0 - s * s), eta, hc, t)[1]);
}

glm::vec3 meanFibreTransmittance(glm::vec3 sigmaA, float eta, float sinTheta) {
  // Midpoint rule over h: the integrand is smooth but for sqrt(1 - h^2) at the edges, where
  // F -> 1 and it goes to 0; 256 points leave an error below 1e-4.
  constexpr int kSteps = 256;
  glm::dvec3 sum(0.0);
  for (int i = 0; i < kSteps; ++i) {
    const float h = float(-1.0 + (i + 0.5) * 2.0 / kSteps);
    sum += glm::dvec3(fibreTransmittance(sigmaA, eta, h, sinTheta));
  }
  return glm::vec3(sum / double(kSteps));
}

namespace hair {

double logI0(double x) {
  x = std::abs(x);
  if (x <= 30.0) {
    // Power series sum_k (x^2/4)^k / (k!)^2; all terms positive, so it converges cleanly.
    const double q = 0.25 * x * x;
    double term = 1.0, sum = 1.0;
    for (int k = 1; k < 200 && term > 1e-17 * sum; ++k) {
      term *= q / (double(k) * k);
      sum += term;
    }
    return std::log(sum);
  }
  // Large x: I0 ~ e^x / sqrt(2 pi x) * (1 + 1/(8x) + 9/(2 (8x)^2) + ...); five terms leave a
  // relative error below 1e-10 from x = 30 on.
  const double t = 1.0 / (8.0 * x);
  double term = 1.0, series = 1.0;
  for (int k = 1; k <= 5; ++k) {
    term *= (2.0 * k - 1) * (2.0 * k - 1) * t / k;
    series += term;
  }
  return x - 0.5 * std::log(2.0 * kPi * x) + std::log(series);
}

double Mp(double cosThetaI, double cosThetaO, double sinThetaI, double sinThetaO, double v) {
  const double a = cosThetaI * cosThetaO / v;
  const double b = sinThetaI * sinThetaO / v;
  // csch(1/v) / (2v) = e^(-1/v) / (v (1 - e^(-2/v))): in logs it holds for every v, where the
  // direct form overflows sinh and I0 once v is below about 1/700.
  const double logNorm = -1.0 / v - std::log(v) - std::log(-std::expm1(-2.0 / v));
  return std::exp(logI0(a) - b + logNorm);
}

double fresnelDielectric(double cosThetaI, double eta) {
  cosThetaI = std::clamp(cosThetaI, 0.0, 1.0);
  const double sinThetaT = safeSqrt(1.0 - cosThetaI * cosThetaI) / eta;
  if (sinThetaT >= 1.0) return 1.0;
  const double cosThetaT = safeSqrt(1.0 - sinThetaT * sinThetaT);
  const double rs = (cosThetaI - eta * cosThetaT) / (cosThetaI + eta * cosThetaT);
  const double rp = (eta * cosThetaI - cosThetaT) / (eta * cosThetaI + cosThetaT);
  return 0.5 * (rs * rs + rp * rp);
}

std::array<glm::dvec3, kHairPMax + 1> Ap(double cosThetaO, double eta, double h, glm::dvec3 t) {
  // One Fresnel factor for every interface, the entry one's (the paper's simplification).
  const double cosGammaO = safeSqrt(1.0 - h * h);
  const double f = fresnelDielectric(cosThetaO * cosGammaO, eta);
  std::array<glm::dvec3, kHairPMax + 1> ap;
  ap[0] = glm::dvec3(f);
  ap[1] = (1.0 - f) * (1.0 - f) * t;
  for (int p = 2; p < kHairPMax; ++p) ap[p] = ap[p - 1] * t * f;
  // Orders kHairPMax and up: ap[kHairPMax-1] * (f t) / (1 - f t). Where f t = 1 (grazing,
  // no absorption) the previous terms are already 0.
  for (int c = 0; c < 3; ++c) {
    const double ft = f * t[c];
    ap[kHairPMax][c] = ap[kHairPMax - 1][c] > 0.0 ? ap[kHairPMax - 1][c] * ft / (1.0 - ft) : 0.0;
  }
  return ap;
}

double trimmedLogistic(double x, double s) {
  const double e = std::exp(-std::abs(x) / s);
  return e / (s * (1.0 + e) * (1.0 + e)) / (logisticCdf(kPi, s) - logisticCdf(-kPi, s));
}

double sampleTrimmedLogistic(double u, double s) {
  // Inverts the logistic's CDF restricted to [-pi, pi].
  const double lo = logisticCdf(-kPi, s);
  const double k = logisticCdf(kPi, s) - lo;
  const double x = -s * std::log(1.0 / (u * k + lo) - 1.0);
  return std::clamp(x, -kPi, kPi);
}

glm::dvec3 crossingTransmittance(double sinThetaO, double eta, double h, glm::dvec3 sigmaA) {
  sinThetaO = std::clamp(sinThetaO, -1.0, 1.0);
  const double cosThetaO = safeSqrt(1.0 - sinThetaO * sinThetaO);
  const double sinThetaT = sinThetaO / eta;
  const double cosThetaT = safeSqrt(1.0 - sinThetaT * sinThetaT);
  // gamma_t from the Bravais index of the projection on the normal plane.
  const double etaP = std::sqrt(eta * eta - sinThetaO * sinThetaO) / std::max(cosThetaO, 1e-12);
  const double sinGammaT = std::clamp(h / etaP, -1.0, 1.0);
  const double cosGammaT = safeSqrt(1.0 - sinGammaT * sinGammaT);
  return glm::exp(-sigmaA * (2.0 * cosGammaT / cosThetaT));
}

double Np(double phi, int p, double s, double gammaO, double gammaT) {
  const double dphi = std::remainder(phi - exitPhi(p, gammaO, gammaT), 2.0 * kPi);
  return trimmedLogistic(dphi, s);
}

}  // namespace hair

struct HairBsdf::Outgoing {
  double sinThetaO = 0, cosThetaO = 1, phiO = 0, gammaT = 0;
  std::array<glm::dvec3, kHairPMax + 1> ap;
  std::array<double, kHairPMax + 1> apPdf{};
  std::array<double, kHairPMax + 1> sinThetaOp{}, cosThetaOp{};  // tilted per lobe
};

HairBsdf::HairBsdf(const HairParams& params) : params_(params) {
  checkHairParams(params);
  gammaO_ = std::asin(std::clamp(double(params.h), -1.0, 1.0));
  // The paper's fits from beta to Mp's variance and Np's logistic scale (its eqs. 6 and 7).
  const double bm = params.betaM, bn = params.betaN;
  const double m = 0.726 * bm + 0.812 * bm * bm + 3.7 * std::pow(bm, 20);
  v_[0] = m * m;
  v_[1] = 0.25 * v_[0];
  v_[2] = 4.0 * v_[0];
  for (int p = 3; p <= kHairPMax; ++p) v_[p] = v_[2];
  s_ = std::sqrt(kPi / 8.0) * (0.265 * bn + 1.194 * bn * bn + 5.372 * std::pow(bn, 22));
  const double alpha = double(params.alphaDeg) * kPi / 180.0;
  for (int k = 0; k < 3; ++k) {
    sin2kAlpha_[k] = std::sin(alpha * double(1 << k));
    cos2kAlpha_[k] = std::cos(alpha * double(1 << k));
  }
}

// The scales' tilt (docs/physics-reference.md "Scales"): pbrt-v4's equations (HairBxDF::f
// rotates theta_o per lobe and evaluates Mp(theta_i, theta_o')), with pbrt-v3's sign of alpha:
// the lobes' centres at theta_i + theta_o = -2 alpha (R, toward the root when x points to the
// tip, as Marschner et al. 2003 observe), alpha (TT) and 4 alpha (TRT). So f here is pbrt-v4's
// f with alpha negated. pbrt-v3 rotates theta_i instead: the same centres, but Mp is then not
// normalised over wi (its values differ by up to a third at alpha = 2 degrees); rotating
// theta_o keeps every Mp normalised, so energy is conserved for any alpha and sample() draws
// exactly the density pdf() returns.
void HairBsdf::tiltedThetaO(int p, double sinThetaO, double cosThetaO, double& sinOut,
                            double& cosOut) const {
  double sinShift = 0.0, cosShift = 1.0;  // theta_o' = theta_o + shift
  if (p == 0) {
    sinShift = sin2kAlpha_[1];  // +2 alpha
    cosShift = cos2kAlpha_[1];
  } else if (p == 1) {
    sinShift = -sin2kAlpha_[0];  // -alpha
    cosShift = cos2kAlpha_[0];
  } else if (p == 2) {
    sinShift = -sin2kAlpha_[2];  // -4 alpha
    cosShift = cos2kAlpha_[2];
  }
  sinOut = sinThetaO * cosShift + cosThetaO * sinShift;
  // Past the pole the rotated direction is the mirror one with cos >= 0: same Mp.
  cosOut = std::abs(cosThetaO * cosShift - sinThetaO * sinShift);
}

HairBsdf::Outgoing HairBsdf::outgoing(glm::dvec3 wo) const {
  Outgoing o;
  o.sinThetaO = std::clamp(wo.x, -1.0, 1.0);
  o.cosThetaO = safeSqrt(1.0 - o.sinThetaO * o.sinThetaO);
  o.phiO = std::atan2(wo.z, wo.y);
  const double eta = params_.eta, h = params_.h;
  // The refracted ray: its longitudinal angle (Snell in theta), and its azimuthal angle
  // gamma_t inside the fibre from the Bravais index of the projection on the normal plane.
  const double etaP = std::sqrt(eta * eta - o.sinThetaO * o.sinThetaO) / o.cosThetaO;
  o.gammaT = std::asin(std::clamp(h / etaP, -1.0, 1.0));
  // One crossing of a fibre of radius 1: path length 2 cos(gamma_t) / cos(theta_t).
  const glm::dvec3 t = hair::crossingTransmittance(o.sinThetaO, eta, h, glm::dvec3(params_.sigmaA));
  o.ap = hair::Ap(o.cosThetaO, eta, h, t);
  double sum = 0;
  for (const glm::dvec3& a : o.ap) sum += luminance(a);
  for (int p = 0; p <= kHairPMax; ++p) o.apPdf[p] = sum > 0 ? luminance(o.ap[p]) / sum : 0.0;
  for (int p = 0; p <= kHairPMax; ++p)
    tiltedThetaO(p, o.sinThetaO, o.cosThetaO, o.sinThetaOp[p], o.cosThetaOp[p]);
  return o;
}

template <class Weight>
Weight HairBsdf::weightedLobes(const Outgoing& o, glm::dvec3 wi,
                               const std::array<Weight, kHairPMax + 1>& weight) const {
  const double sinThetaI = std::clamp(wi.x, -1.0, 1.0);
  const double cosThetaI = safeSqrt(1.0 - sinThetaI * sinThetaI);
  const double phi = std::atan2(wi.z, wi.y) - o.phiO;
  Weight sum(0.0);
  for (int p = 0; p < kHairPMax; ++p)
    sum += hair::Mp(cosThetaI, o.cosThetaOp[p], sinThetaI, o.sinThetaOp[p], v_[p]) * weight[p] *
           hair::Np(phi, p, s_, gammaO_, o.gammaT);
  // The higher orders: spread uniformly in azimuth.
  sum += hair::Mp(cosThetaI, o.cosThetaOp[kHairPMax], sinThetaI, o.sinThetaOp[kHairPMax],
                  v_[kHairPMax]) *
         weight[kHairPMax] / (2.0 * kPi);
  return sum;
}

glm::vec3 HairBsdf::fCos(glm::vec3 wo, glm::vec3 wi) const {
  const Outgoing o = outgoing(glm::dvec3(wo));
  return glm::vec3(weightedLobes(o, glm::dvec3(wi), o.ap));
}

glm::vec3 HairBsdf::f(glm::vec3 wo, glm::vec3 wi) const {
  const Outgoing o = outgoing(glm::dvec3(wo));
  const glm::dvec3 sum = weightedLobes(o, glm::dvec3(wi), o.ap);
  const double cosN = std::abs(double(wi.z));
  return glm::vec3(cosN > 0 ? sum / cosN : sum);
}

float HairBsdf::pdf(glm::vec3 wo, glm::vec3 wi) const {
  const Outgoing o = outgoing(glm::dvec3(wo));
  return float(weightedLobes(o, glm::dvec3(wi), o.apPdf));
}

HairBsdf::Sample HairBsdf::sample(glm::vec3 wo, glm::vec2 u0, glm::vec2 u1) const {
  const Outgoing o = outgoing(glm::dvec3(wo));
  Sample out;
  // The lobe: p with probability apPdf[p].
  double u = u0.x;
  int p = 0;
  for (; p < kHairPMax; ++p) {
    if (u < o.apPdf[p]) break;
    u -= o.apPdf[p];
  }
  out.lobe = p;

  // theta_i from Mp: Mp is a von Mises-Fisher lobe about the direction at theta = -theta_o'
  // integrated over azimuth, so draw the vMF's angle psi from its axis (its CDF in cos psi
  // inverted) and a uniform azimuth xi about it, and keep the result's latitude.
  const double v = v_[p];
  const double um = u1.x;
  double logTerm = std::log(um + (1.0 - um) * std::exp(-2.0 / v));
  if (!std::isfinite(logTerm)) logTerm = -2.0 / v;  // um = 0 with exp(-2/v) underflowing
  const double cosPsi = std::clamp(1.0 + v * logTerm, -1.0, 1.0);
  const double sinPsi = safeSqrt(1.0 - cosPsi * cosPsi);
  const double cosXi = std::cos(2.0 * kPi * double(u1.y));
  const double sinThetaI =
      std::clamp(-cosPsi * o.sinThetaOp[p] + sinPsi * cosXi * o.cosThetaOp[p], -1.0, 1.0);
  const double cosThetaI = safeSqrt(1.0 - sinThetaI * sinThetaI);

  // phi_i from Np (the last term is uniform in azimuth).
  const double dphi = p < kHairPMax
                          ? exitPhi(p, gammaO_, o.gammaT) + hair::sampleTrimmedLogistic(u0.y, s_)
                          : 2.0 * kPi * double(u0.y);
  const double phiI = o.phiO + dphi;
  const glm::dvec3 wi(sinThetaI, cosThetaI * std::cos(phiI), cosThetaI * std::sin(phiI));
  out.wi = glm::vec3(wi);

  const glm::dvec3 sum = weightedLobes(o, wi, o.ap);
  const double pdf = weightedLobes(o, wi, o.apPdf);
  const double cosN = std::abs(wi.z);
  out.f = glm::vec3(cosN > 0 ? sum / cosN : sum);
  out.pdf = float(pdf);
  out.weight = pdf > 0 ? glm::vec3(sum / pdf) : glm::vec3(0.0f);
  return out;
}

std::array<glm::vec3, kHairPMax + 1> HairBsdf::ap(glm::vec3 wo) const {
  const Outgoing o = outgoing(glm::dvec3(wo));
  std::array<glm::vec3, kHairPMax + 1> a;
  for (int p = 0; p <= kHairPMax; ++p) a[p] = glm::vec3(o.ap[p]);
  return a;
}

std::array<float, kHairPMax + 1> HairBsdf::lobePdf(glm::vec3 wo) const {
  const Outgoing o = outgoing(glm::dvec3(wo));
  std::array<float, kHairPMax + 1> a;
  for (int p = 0; p <= kHairPMax; ++p) a[p] = float(o.apPdf[p]);
  return a;
}

}  // namespace sb::pbr
