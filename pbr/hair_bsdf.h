// The hair BSDF of Chiang, Bitterli, Tappan and Burley 2016 ("A Practical and Controllable Hair
// and Fur Model for Production Path Tracing") with the parameters and conventions of pbrt-v3's
// HairBSDF: the first piece of a path-traced strand reference (docs/physics-reference.md).
//
// Frame: x along the fibre's tangent (root to tip), z the normal of the surface that was hit,
// y = z cross x. A direction w has sin(theta) = w.x (theta measured from the normal plane) and
// phi = atan2(w.z, w.y). wo points away from the fibre toward the viewer, wi toward the light;
// both unit length.
//
// f(wo, wi) is divided by |wi.z| as pbrt's is: an integrator multiplies it by |cos| = |wi.z| and
// gets the model's sum over lobes of Mp * Ap * Np, which fCos() returns directly. That sum is
// normalised over the sphere: Mp over theta_i with the measure cos(theta_i) dtheta_i, Np over
// phi, so a fibre without absorption scatters exactly what it receives (the white furnace).
//
// Computed in double: the reference should not be limited by float round-off in the Bessel
// terms of narrow lobes. The API takes and returns float (glm) like the rest of the project.
#pragma once

#include <array>
#include <glm/glm.hpp>

namespace sb::pbr {

// Lobes R (p = 0), TT (1), TRT (2), and one term for all higher orders (p = 3).
inline constexpr int kHairPMax = 3;

struct HairParams {
  float h = 0.0f;  // offset across the fibre where the ray hit it, in [-1, 1]
  float eta = 1.55f;
  // Absorption per unit path length, a fibre's radius being 1, per RGB channel (>= 0).
  // The default: pbrt's default hair, sigmaAFromConcentration(1.3, 0).
  glm::vec3 sigmaA{0.5447f, 0.9061f, 1.781f};
  float betaM = 0.3f;     // longitudinal roughness, (0, 1]
  float betaN = 0.3f;     // azimuthal roughness, (0, 1]
  float alphaDeg = 2.0f;  // tilt of the cuticle scales, degrees
};

// Throws sb::InputError (base/errors.h) naming the parameter out of range.
void checkHairParams(const HairParams& p);

// Absorption of a fibre with these melanin concentrations (the paper's eq. 8, its RGB
// absorption coefficients of eumelanin and pheomelanin).
glm::vec3 sigmaAFromConcentration(float eumelanin, float pheomelanin);
// The absorption that gives roughly this diffuse colour (each channel in (0, 1]) after
// multiple scattering in a head of hair, by the paper's fit in beta_n (its eq. 9).
glm::vec3 sigmaAFromReflectance(glm::vec3 color, float betaN);

// How much light a fibre lets through (docs/physics-reference.md "Fibres that attenuate"): the
// TT lobe's attenuation A1 = (1 - F)^2 T for a ray crossing the fibre at offset h (in [-1, 1])
// and at sin(theta) = sinTheta to its normal plane (F: Fresnel at cos(theta) cos(gamma); T: one
// crossing of the refracted path, exp(-sigma_a 2 cos(gamma_t) / cos(theta_t)), radius 1). It
// is what rung 2's shadow and camera rays keep through each fibre they cross, treated as going
// straight on. Even in h and in sinTheta.
glm::vec3 fibreTransmittance(glm::vec3 sigmaA, float eta, float h, float sinTheta);
// The same averaged over h uniform in [-1, 1] (over the fibre's projected width): a fibre's
// transmittance as a raster sees it, so 1 - this (per channel, or its luminance) is a physical
// shadow_alpha for a strand covering the whole of a texel.
glm::vec3 meanFibreTransmittance(glm::vec3 sigmaA, float eta, float sinTheta);

// The lobe terms, exposed so that tests can check each one against the paper's equations.
namespace hair {
// log of the modified Bessel function I0, finite for large x where I0 overflows.
double logI0(double x);
// d'Eon et al. 2011's longitudinal lobe of variance v, normalised so that its integral over
// theta_i in [-pi/2, pi/2] with the measure cos(theta_i) is 1; evaluated in log space so that
// narrow lobes (small v, large Bessel and sinh terms) stay finite.
double Mp(double cosThetaI, double cosThetaO, double sinThetaI, double sinThetaO, double v);
// Unpolarised Fresnel reflectance of a dielectric of index eta seen from outside (index 1).
double fresnelDielectric(double cosThetaI, double eta);
// Attenuation of each lobe: Fresnel at cos(theta_o) * cos(gamma_o) and the transmittance t of
// one crossing of the fibre; the last entry sums the orders past kHairPMax - 1 (a geometric
// series).
std::array<glm::dvec3, kHairPMax + 1> Ap(double cosThetaO, double eta, double h, glm::dvec3 t);
// Azimuthal lobe p: the logistic of scale s trimmed to [-pi, pi], centred on the exit angle
// Phi(p) = 2 p gamma_t - 2 gamma_o + p pi of the ideal smooth cylinder.
double Np(double phi, int p, double s, double gammaO, double gammaT);
double trimmedLogistic(double x, double s);  // on [-pi, pi], normalised there
double sampleTrimmedLogistic(double u, double s);
// Transmittance of one crossing of the fibre (radius 1) by the ray refracted at offset h, the
// outside ray at sin(theta_o) to the normal plane: exp(-sigma_a 2 cos(gamma_t) / cos(theta_t)).
glm::dvec3 crossingTransmittance(double sinThetaO, double eta, double h, glm::dvec3 sigmaA);
}  // namespace hair

class HairBsdf {
 public:
  explicit HairBsdf(const HairParams& params);  // checkHairParams first

  // pbrt's f: sum over lobes of Mp * Ap * Np, divided by |wi.z| (see the header's top).
  glm::vec3 f(glm::vec3 wo, glm::vec3 wi) const;
  // f * |wi.z|: what multiplies incident radiance in the integral over solid angle.
  glm::vec3 fCos(glm::vec3 wo, glm::vec3 wi) const;
  // Density of sample()'s wi per unit solid angle.
  float pdf(glm::vec3 wo, glm::vec3 wi) const;

  struct Sample {
    glm::vec3 wi{0.0f};
    glm::vec3 f{0.0f};       // f(wo, wi)
    glm::vec3 weight{0.0f};  // f * |wi.z| / pdf
    float pdf = 0.0f;        // of wi, all lobes together (not just the one drawn)
    int lobe = 0;            // the p that was drawn
  };
  // Draws a lobe by its luminance share of Ap (u0.x), then theta_i from its Mp (u1) and
  // phi_i from its Np (u0.y). Each u in [0, 1).
  Sample sample(glm::vec3 wo, glm::vec2 u0, glm::vec2 u1) const;

  // Per-lobe attenuation Ap for this wo (the lobes' share of what is scattered).
  std::array<glm::vec3, kHairPMax + 1> ap(glm::vec3 wo) const;
  // The probability sample() draws each lobe with, for this wo.
  std::array<float, kHairPMax + 1> lobePdf(glm::vec3 wo) const;

  const HairParams& params() const { return params_; }
  double variance(int p) const { return v_[p]; }  // of Mp for lobe p
  double logisticScale() const { return s_; }     // of Np

 private:
  struct Outgoing;  // what depends on wo alone
  Outgoing outgoing(glm::dvec3 wo) const;
  // sin and cos of theta_o rotated by lobe p's scale tilt.
  void tiltedThetaO(int p, double sinThetaO, double cosThetaO, double& sinOut,
                    double& cosOut) const;
  // The lobes Mp Np summed with a weight each: their Ap (the BSDF) or the
  // probability of drawing them (the pdf).
  template <class Weight>
  Weight weightedLobes(const Outgoing& o, glm::dvec3 wi,
                       const std::array<Weight, kHairPMax + 1>& weight) const;

  HairParams params_;
  double gammaO_ = 0;
  std::array<double, kHairPMax + 1> v_{};
  double s_ = 0;
  std::array<double, 3> sin2kAlpha_{}, cos2kAlpha_{};  // sin and cos of 2^k alpha
};

}  // namespace sb::pbr
