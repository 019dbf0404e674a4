// --shading sadeghi.
#include "techniques/common/unit.h"

#include <algorithm>
#include <cmath>

#include "techniques/sadeghi/sadeghi.h"

SB_TECHNIQUE(
    {.name = "sadeghi",
     .family = Family::Shading,
     .folder = "sadeghi",
     .paper = "Sadeghi et al. 2010 (as Kraft 2018 implements it)",
     .help = "Sadeghi et al. 2010, the artist-friendly model as Kraft 2018 implements it (eqs. "
             "20-24; defaults: Listing 2, diffuse 0.4, specular 1, no ambient, the glints at the "
             "TT width)",
     .options = opt::lobes(
         "weight of the Kajiya-Kay diffuse term (the thesis: 0.4), 0..4",
         "weight of the specular sum (Listing 2: 1, R + TT + TRT unweighted), 0..4",
         {opt::number("i_r", "1", 0, 10, "intensity of the primary highlight R, 0..10"),
          opt::number("i_tt", "1", 0, 10, "intensity of the transmission TT, 0..10"),
          opt::number("i_trt", "1", 0, 10, "intensity of the secondary highlight TRT, 0..10"),
          opt::number("tt_width", "10", 1, 90, "azimuthal width of TT in degrees, 1..90"),
          opt::number("glint", "0.5", 0, 10, "relative intensity of the glints I_g, 0..10"),
          opt::number("glint_angle", "35", 0, 90,
                      "glints' half angle in degrees (the thesis: 30..45), 0..90"),
          opt::number("glint_width", "0", 0, 90,
                      "azimuthal width of the glints in degrees; 0: tt_width (Listing 2's one "
                      "azi_width), 0..90"),
          opt::number("ambient", "0", 0, 1,
                      "ambient term, a fraction of the hair colour (Listing 2: none), 0..1")},
         "1"),
     .makeShading = [](const OptionReader& o) {
       const auto f = [&](const char* name) { return static_cast<float>(o.number(name)); };
       const ShadingLobes lobes = ShadingLobes::read(o);
       SadeghiParams p{};
       p.sadeghiAlpha = lobes.alpha;
       p.sadeghiBeta = lobes.beta;
       p.sadeghiIntensity = {f("i_r"), f("i_tt"), f("i_trt"), f("glint")};
       p.sadeghiDiffuse = lobes.diffuse;
       p.sadeghiSpecular = lobes.specular;
       p.sadeghiGlintAngle = f("glint_angle") * kDegree;
       p.sadeghiTtWidth = f("tt_width") * kDegree;
       p.sadeghiGlintWidth = (f("glint_width") > 0.0f ? f("glint_width") : f("tt_width")) * kDegree;
       ShadingModel m;
       m.setParams(p);
       m.ambient = f("ambient");
       // The specular sum's largest value: every lobe at its peak, over the shader's bound on
       // cos^2(theta_d).
       const glm::vec4 i = p.sadeghiIntensity;
       m.maxDirect =
           p.sadeghiDiffuse + p.sadeghiSpecular * ((i.x + i.y + i.z * (1.0f + i.w)) / kMinCos2);
       m.direct = [p](glm::vec3 T, glm::vec3 L, glm::vec3 V, glm::vec3 c) {
         const float tl = glm::dot(T, L);
         const float diffuse = std::sqrt(std::max(0.0f, 1.0f - tl * tl));
         return p.sadeghiDiffuse * diffuse * c + p.sadeghiSpecular * sadeghiSpecular(p, T, L, V, c);
       };
       return m;
     }});
