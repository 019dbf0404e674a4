// --shadow osm: opacity shadow maps.
#include "render/common/unit.h"

#include "techniques/osm/osm.h"

SB_TECHNIQUE(
    {.name = "osm",
     .family = Family::Shadow,
     .folder = "osm",
     .paper = "Kim & Neumann 2001",
     .help = "opacity shadow maps (Kim & Neumann 2001): planar opacity maps, linear interpolation",
     .options = {opt::integer("maps", 16, 1, 512, "number of opacity maps, 1..512"),
                 opt::choice("slicing", "uniform", {"uniform", "density", "gamma"},
                             "uniform | density (equal hair points per slice) | gamma (tighter "
                             "near the light)"),
                 opt::number("gamma", "2", 0.1, 10.0,
                             "slicing=gamma exponent: D_i = near + (far-near)(i/n)^gamma, 0.1..10"),
                 opt::choice("passes", "multi", {"single", "multi"},
                             "single (one hair pass per map, the original) | multi (up to 6 "
                             "targets x 4 maps a pass)"),
                 opt::choice("bits", "32", {"8", "16", "32"},
                             "8 (RGBA8 unorm, kappa-scaled: the paper's limited-bit maps) | 16 "
                             "(RGBA16F: half float counts, not kappa-scaled; exact to 2048 "
                             "fragments) | 32 (RGBA32F)"),
                 opt::number("kappa", "0", 0.0, 100.0,
                             "bits=8: e^-kappa at opacity 1; 0 derives 8 ln 2 (the paper), 0..100"),
                 opt::mapSize(), opt::bias(), opt::opacityFilter()},
     .stepped = SteppedOption{"maps", true, 1, 256},
     .makeShadow = [](const OptionReader& o) {
       return std::make_unique<OpacityShadowMaps>(OpacityShadowMaps::readOptions(o));
     }});
