// --shading sadeghi.
#include "render/common/unit.h"

namespace sb {
namespace {
struct O {
  ShadingModel::Lobes lobes;
  float iR, iTT, iTRT, ttWidth, glint, glintAngle, glintWidth, ambient;
};
const OptionTable<O> kOptions(
    {opt::lobes(&O::lobes, "weight of the Kajiya-Kay diffuse term (the thesis: 0.4), 0..4",
                "weight of the specular sum (Listing 2: 1, R + TT + TRT unweighted), 0..4", "1"),
     opt::number(&O::iR, "i_r", "1", 0, 10, "intensity of the primary highlight R, 0..10"),
     opt::number(&O::iTT, "i_tt", "1", 0, 10, "intensity of the transmission TT, 0..10"),
     opt::number(&O::iTRT, "i_trt", "1", 0, 10, "intensity of the secondary highlight TRT, 0..10"),
     opt::number(&O::ttWidth, "tt_width", "10", 1, 90, "azimuthal width of TT in degrees, 1..90"),
     opt::number(&O::glint, "glint", "0.5", 0, 10, "relative intensity of the glints I_g, 0..10"),
     opt::number(&O::glintAngle, "glint_angle", "35", 0, 90,
                 "glints' half angle in degrees (the thesis: 30..45), 0..90"),
     opt::number(&O::glintWidth, "glint_width", "0", 0, 90,
                 "azimuthal width of the glints in degrees; 0: tt_width (Listing 2's one "
                 "azi_width), 0..90"),
     opt::number(&O::ambient, "ambient", "0", 0, 1,
                 "ambient term, a fraction of the hair colour (Listing 2: none), 0..1")});
}  // namespace
}  // namespace sb

SB_TECHNIQUE(
    {.name = "sadeghi",
     .family = Family::Shading,
     .folder = "sadeghi",
     .paper = "Sadeghi et al. 2010 (as Kraft 2018 implements it)",
     .help = "Sadeghi et al. 2010, the artist-friendly model as Kraft 2018 implements it (eqs. "
             "20-24; defaults: Listing 2, diffuse 0.4, specular 1, no ambient, the glints at the "
             "TT width)",
     .options = kOptions.infos(),
     .makeShading = [](const OptionReader& r) {
       const O o = kOptions.read(r);
       ShadingModel m = ShadingModel::withLobes(o.lobes);
       m.kind = ShadingKind::Sadeghi;
       m.shift.w = o.glintAngle * kDegree;
       m.width.w = o.ttWidth * kDegree;
       m.intensity = {o.iR, o.iTT, o.iTRT, o.glint};
       m.glintWidth = (o.glintWidth > 0.0f ? o.glintWidth : o.ttWidth) * kDegree;
       m.material.w = o.ambient;
       return m;
     }});
