// --shading kajiya-kay.
#include "render/common/unit.h"

SB_TECHNIQUE(
    {.name = "kajiya-kay",
     .family = Family::Shading,
     .folder = "kajiya_kay",
     .paper = "Kajiya & Kay 1989",
     .help = "Kajiya & Kay 1989: diffuse sin(T,L), specular cos^shininess on the reflection cone",
     .options = {opt::number("diffuse", "0.8", 0, 4, "diffuse weight, 0..4"),
                 opt::number("specular", "0.35", 0, 4, "specular weight, 0..4"),
                 opt::number("shininess", "40", 1, 1000, "specular exponent, 1..1000"),
                 opt::number("ambient", "0.12", 0, 1,
                             "ambient term, a fraction of the hair colour (0: none, as the "
                             "path-traced reference has), 0..1")},
     .isDefault = true,
     .makeShading = [](const OptionReader& o) {
       const auto f = [&](const char* name) { return static_cast<float>(o.number(name)); };
       ShadingModel m;
       m.kind = ShadingKind::KajiyaKay;
       m.material = {f("diffuse"), f("specular"), f("shininess"), f("ambient")};
       return m;
     }});
