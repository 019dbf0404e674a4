// --shadow dom: deep opacity maps.
#include "render/common/unit.h"

#include "techniques/dom/dom.h"

SB_TECHNIQUE(
    {.name = "dom",
     .family = Family::Shadow,
     .folder = "dom",
     .paper = "Yuksel & Keyser 2008",
     .help = "deep opacity maps (Yuksel & Keyser 2008): layers that follow the hair from its first "
             "depth",
     .options =
         {opt::integer("layers", 3, 1, DeepOpacityMaps::kMaxLayers,
                       "opacity layers K, 1..31 (K = 4n-1 fills n RGBA layers of one array)"),
          opt::choice("spacing", "linear",
                      {"constant", "linear", "pow2", "fibonacci", "list", "power"},
                      "constant | linear | pow2 | fibonacci | list (layer sizes) | power "
                      "(Unreal: K s (k/K)^2.8)"),
          opt::text("list", "1;2;3",
                    "spacing=list: layer sizes as multiples of the layer size, ';'-separated"),
          opt::number("size_abs", "0", 0.0, 1.0,
                      "layer size in light depth units (0: use size_frac), 0..1"),
          opt::number("size_frac", "0.1", 1e-6, 100.0,
                      "layer size as a fraction of the hair's depth range from the light"),
          opt::choice("beyond", "last", {"ignore", "last", "extend"},
                      "fragments beyond the last layer: ignore | last | extend"),
          opt::choice("depth_bits", "32", {"8", "16", "32"},
                      "precision of z0 (the depth-only pass's 32-bit float depth map), "
                      "quantized where read: 8 | 16 | 32"),
          opt::choice("counting", "yuksel", {"yuksel", "thesis"},
                      "yuksel (a fragment counts in its own layer and every later one, the "
                      "paper) | thesis (its own and every preceding one, Kraft 2018 Listing 3)"),
          opt::opacityFilter(), opt::mapSize(), opt::bias()},
     .stepped = SteppedOption{"layers", false, 1, 31},
     .makeShadow = [](const OptionReader& o) {
       return std::make_unique<DeepOpacityMaps>(DeepOpacityMaps::readOptions(o));
     }});
