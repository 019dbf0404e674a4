// --oit compute_raster: strands rasterized in compute shaders, as engines do.
#include "render/common/unit.h"

#include "techniques/compute_raster/compute_raster.h"

namespace sb {
namespace {
using O = ComputeRasterOit::Options;
const OptionTable<O> kOptions(
    {opt::choice(&O::tile, "tile", "8", {{"8", 8u}, {"16", 16u}},
                 "tile side in pixels (one workgroup per tile)"),
     opt::integer(&O::fragments, "fragments", 0, 0, 16777216,
                  "list entries per tile (16 bytes each); 0: as many as a counting pass "
                  "finds; a full list drops fragments (counted and warned), 0..16777216"),
     opt::choice(&O::analytic, "coverage", "analytic", {{"analytic", true}, {"binary", false}},
                 "analytic: the strand's width inside each pixel (a box filter across "
                 "it); binary: pixel centres inside it, as the hardware rasterizes"),
     opt::choice(&O::perPoint, "shading", "point", {{"point", true}, {"fragment", false}},
                 "point: each segment end shaded once, interpolated; fragment: every "
                 "fragment shaded"),
     opt::number(&O::width, "width", "0", 0.0, 64.0,
                 "strand width in pixels; 0: the frame's (lines 1, --ribbon-width)"),
     opt::choice(&O::thickness, "width_from", "frame", {{"frame", false}, {"thickness", true}},
                 "frame: width= pixels (or the frame's); thickness: the scene's strand "
                 "thickness (world units) projected at each pixel's depth, so far or thin "
                 "strands cover a sliver of a pixel"),
     opt::number(&O::lod, "lod", "1", 0.0, 1.0,
                 "share of strands kept (by a hash of the root), (0, 1]; the kept ones "
                 "stand for the rest"),
     opt::number(&O::lodWiden, "lod_widen", "2", 1.0, 16.0,
                 "most the kept strands are widened (the rest of the LOD's compensation "
                 "goes to opacity), 1..16"),
     opt::number(&O::terminate, "terminate", "0.0009765625", 0.0, 0.5,
                 "a pixel stops compositing when the transmittance left is under this")},
    ComputeRasterOit::check);
}  // namespace
}  // namespace sb

SB_TECHNIQUE(
    {.name = "compute_raster",
     .family = Family::Transparency,
     .folder = "compute_raster",
     .paper = "Frostbite (Every Strand Counts), Unity Enemies, Unreal HairStrands",
     .help = "compute strand rasterizer: segments walked into screen tiles' lists with analytic "
             "coverage from the strand width, each tile bucketed by pixel and composited front to "
             "back in depth order with early termination; LOD thins strands, widening the rest",
     .options = kOptions.infos(),
     .caps =
         {.msaaRefusal =
              "it rasterizes in compute with its own per-pixel coverage (coverage=analytic is its "
              "anti-aliasing) and no hardware targets: the frame's samples would not be used",
          .meshRefusal = "its compute passes read the strands' points and segments"},
     .makeOit = build<ComputeRasterOit>(kOptions)});
