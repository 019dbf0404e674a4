// `strandbench bsdf-probe`: the hair BSDF of the path-traced reference (pbr/hair_bsdf.h) for
// one pair of directions, as JSON: f, pdf, each lobe's Ap, and the parameters used. A look at
// the physics without a renderer (docs/physics-reference.md).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "pbr/hair_bsdf.h"

namespace sb {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct BsdfProbeRequest {
  std::string wo, wi, woDeg, wiDeg;
  std::string sigmaA, color, melanin, sample;
  pbr::HairParams params;
};

// "a,b,c" as exactly n finite numbers, or an InputError naming the option and the form.
std::vector<double> parseNumbers(const std::string& option, const std::string& text, int n,
                                 const std::string& form) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    double x = 0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(x))
      throw InputError(option + " " + text + ": expected " + form);
    values.push_back(x);
  }
  if (int(values.size()) != n || (!text.empty() && text.back() == ','))
    throw InputError(option + " " + text + ": expected " + form);
  return values;
}

glm::vec3 parseVec3(const std::string& option, const std::string& text, const std::string& form) {
  const std::vector<double> v = parseNumbers(option, text, 3, form);
  return glm::vec3(float(v[0]), float(v[1]), float(v[2]));
}

// A direction from --NAME X,Y,Z (normalised here) or --NAME-deg THETA,PHI.
glm::vec3 direction(const std::string& name, const std::string& vector,
                    const std::string& degrees) {
  const std::string option = "--" + name, optionDeg = "--" + name + "-deg";
  if (!vector.empty() && !degrees.empty())
    throw InputError("give " + option + " or " + optionDeg + ", not both");
  if (vector.empty() && degrees.empty())
    throw InputError("give " + option + " X,Y,Z or " + optionDeg + " THETA,PHI");
  if (!vector.empty()) {
    const std::vector<double> v = parseNumbers(option, vector, 3, "X,Y,Z (three numbers)");
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(length > 1e-12))
      throw InputError(option + " " + vector + ": a direction must not be zero");
    return glm::vec3(float(v[0] / length), float(v[1] / length), float(v[2] / length));
  }
  const std::vector<double> a =
      parseNumbers(optionDeg, degrees, 2, "THETA,PHI in degrees (two numbers)");
  if (!(std::abs(a[0]) <= 90.0))
    throw InputError(optionDeg + " " + degrees + ": theta must be in [-90, 90] degrees");
  const double theta = a[0] * kDeg, phi = a[1] * kDeg;
  return glm::vec3(float(std::sin(theta)), float(std::cos(theta) * std::cos(phi)),
                   float(std::cos(theta) * std::sin(phi)));
}

// A float as the shortest decimal that reads back as it (0.1, not 0.10000000149011612): the
// BSDF's results are floats, and their double widening is noise.
double num(double x) {
  const float f = float(x);
  if (!std::isfinite(f)) return x;
  char buf[32];
  const auto end = std::to_chars(buf, buf + sizeof buf, f).ptr;
  return std::strtod(std::string(buf, end).c_str(), nullptr);
}

nlohmann::json vec(glm::vec3 v) { return {num(v.x), num(v.y), num(v.z)}; }

nlohmann::json directionJson(glm::vec3 w) {
  const double theta = std::asin(std::clamp(double(w.x), -1.0, 1.0)) / kDeg;
  const double phi = std::atan2(double(w.z), double(w.y)) / kDeg;
  return {{"dir", vec(w)}, {"theta_deg", num(theta)}, {"phi_deg", num(phi)}};
}

int runBsdfProbe(BsdfProbeRequest r) {
  const glm::vec3 wo = direction("wo", r.wo, r.woDeg);
  const glm::vec3 wi = direction("wi", r.wi, r.wiDeg);
  const int sources = !r.sigmaA.empty() + !r.color.empty() + !r.melanin.empty();
  if (sources > 1) throw InputError("give at most one of --sigma-a, --color and --melanin");
  std::string from = "default (eumelanin 1.3)";
  nlohmann::json extra = nlohmann::json::object();
  if (!r.sigmaA.empty()) {
    r.params.sigmaA = parseVec3("--sigma-a", r.sigmaA, "R,G,B (three numbers)");
    from = "sigma-a";
  } else if (!r.color.empty()) {
    const glm::vec3 c = parseVec3("--color", r.color, "R,G,B (three numbers in (0, 1])");
    // beta_n is checked first: its message should name it, not the colour mapping.
    pbr::checkHairParams(r.params);
    r.params.sigmaA = pbr::sigmaAFromReflectance(c, r.params.betaN);
    from = "color";
    extra["color"] = vec(c);
  } else if (!r.melanin.empty()) {
    const std::vector<double> m =
        parseNumbers("--melanin", r.melanin, 2, "EUMELANIN,PHEOMELANIN (two numbers)");
    r.params.sigmaA = pbr::sigmaAFromConcentration(float(m[0]), float(m[1]));
    from = "melanin";
    extra["melanin"] = m;
  }
  const pbr::HairBsdf bsdf(r.params);  // checks the parameters

  const pbr::HairParams& p = bsdf.params();
  nlohmann::json params = {{"h", num(p.h)},
                           {"eta", num(p.eta)},
                           {"sigma_a", vec(p.sigmaA)},
                           {"sigma_a_from", from},
                           {"beta_m", num(p.betaM)},
                           {"beta_n", num(p.betaN)},
                           {"alpha_deg", num(p.alphaDeg)},
                           {"mp_variance", nlohmann::json::array()},
                           {"np_scale", num(bsdf.logisticScale())}};
  for (int k = 0; k <= pbr::kHairPMax; ++k) params["mp_variance"].push_back(num(bsdf.variance(k)));
  params.update(extra);

  nlohmann::json j;
  j["params"] = params;
  j["wo"] = directionJson(wo);
  j["wi"] = directionJson(wi);
  j["f"] = vec(bsdf.f(wo, wi));
  j["f_cos"] = vec(bsdf.fCos(wo, wi));
  j["pdf"] = num(bsdf.pdf(wo, wi));
  const auto ap = bsdf.ap(wo);
  const auto lobePdf = bsdf.lobePdf(wo);
  const char* names[] = {"R", "TT", "TRT", "TRRT+"};
  for (int k = 0; k <= pbr::kHairPMax; ++k)
    j["lobes"].push_back(
        {{"p", k}, {"name", names[k]}, {"ap", vec(ap[k])}, {"pick", num(lobePdf[k])}});
  if (!r.sample.empty()) {
    const std::vector<double> u =
        parseNumbers("--sample", r.sample, 4, "U0,U1,U2,U3 (four numbers in [0, 1))");
    for (double x : u)
      if (!(x >= 0.0 && x < 1.0))
        throw InputError("--sample " + r.sample + ": each number must be in [0, 1)");
    const pbr::HairBsdf::Sample s =
        bsdf.sample(wo, {float(u[0]), float(u[1])}, {float(u[2]), float(u[3])});
    j["sample"] = {{"wi", directionJson(s.wi)},
                   {"f", vec(s.f)},
                   {"pdf", num(s.pdf)},
                   {"weight", vec(s.weight)},
                   {"lobe", s.lobe}};
  }
  std::cout << j.dump(2) << "\n";
  return 0;
}

}  // namespace

void registerBsdfProbeCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "bsdf-probe", "the hair BSDF of the path-traced reference for one pair of directions (JSON)");
  auto r = std::make_shared<BsdfProbeRequest>();
  cmd->add_option("--wo", r->wo, "direction toward the viewer, X,Y,Z in the hair frame");
  cmd->add_option("--wi", r->wi, "direction toward the light, X,Y,Z in the hair frame");
  cmd->add_option("--wo-deg", r->woDeg,
                  "--wo as THETA,PHI in degrees: theta from the normal plane toward the tangent "
                  "(+x), phi from +y toward +z");
  cmd->add_option("--wi-deg", r->wiDeg, "--wi as THETA,PHI in degrees");
  cmd->add_option("--h", r->params.h, "offset across the fibre, -1..1")->capture_default_str();
  cmd->add_option("--eta", r->params.eta, "index of refraction")->capture_default_str();
  cmd->add_option("--sigma-a", r->sigmaA,
                  "absorption R,G,B per unit radius (default: eumelanin 1.3)");
  cmd->add_option("--color", r->color,
                  "absorption from a diffuse colour R,G,B in (0, 1] (Chiang et al.'s mapping)");
  cmd->add_option("--melanin", r->melanin, "absorption from EUMELANIN,PHEOMELANIN");
  cmd->add_option("--beta-m", r->params.betaM, "longitudinal roughness, (0, 1]")
      ->capture_default_str();
  cmd->add_option("--beta-n", r->params.betaN, "azimuthal roughness, (0, 1]")
      ->capture_default_str();
  cmd->add_option("--alpha", r->params.alphaDeg, "cuticle scale tilt, degrees")
      ->capture_default_str();
  cmd->add_option("--sample", r->sample,
                  "also draw one wi for wo from four uniform numbers U0,U1,U2,U3");
  cmd->footer(
      "Frame: x along the fibre's tangent (root to tip), z the surface normal at the hit,\n"
      "y = z cross x; sin(theta) = w.x, phi = atan2(w.z, w.y). Both directions point away\n"
      "from the fibre. f is pbrt's (divided by |wi.z|); f_cos = f |wi.z| is the sum over lobes\n"
      "of Mp Ap Np; pdf is per unit solid angle; each lobe's pick is the chance sampling\n"
      "draws it. Exit 2 on bad input.");
  cmd->callback([r] { runGuarded("bsdf-probe", [&] { return runBsdfProbe(*r); }); });
}

}  // namespace sb
