// --shading marschner.
#include "render/common/unit.h"

namespace sb {
namespace {
struct O {
  ShadingModel::Lobes lobes;
  float eta, caustic, ambient;
};
const OptionTable<O> kOptions(
    {opt::lobes(&O::lobes, "weight of a Kajiya-Kay diffuse term (the thesis adds one), 0..4",
                "weight of the scattering function, 0..4"),
     opt::number(&O::eta, "eta", "1.55", 1.01, 3, "index of refraction of the fibre, 1.01..3"),
     opt::number(&O::caustic, "caustic", "0.5", 0.01, 4,
                 "floor on |dphi/dh| bounding the TRT caustic (the paper fades it with a "
                 "Gaussian), 0.01..4"),
     opt::number(&O::ambient, "ambient", "0.12", 0, 1,
                 "ambient term, a fraction of the hair colour (0: none, as the path-traced "
                 "reference has), 0..1")});
}  // namespace
}  // namespace sb

SB_TECHNIQUE(
    {.name = "marschner",
     .family = Family::Shading,
     .folder = "marschner",
     .paper = "Marschner et al. 2003",
     .help =
         "Marschner et al. 2003: R, TT, TRT lobes, longitudinal Gaussians, azimuthal terms with "
         "Fresnel and absorption (from the strand colour)",
     .options = kOptions.infos(),
     .makeShading = [](const OptionReader& r) {
       const O o = kOptions.read(r);
       ShadingModel m = ShadingModel::withLobes(o.lobes);
       m.kind = ShadingKind::Marschner;
       m.shift.w = o.eta;
       m.width.w = o.caustic;
       m.material.w = o.ambient;
       return m;
     }});
