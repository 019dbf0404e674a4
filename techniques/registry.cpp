// The shadow and transparency techniques by name, with their options and defaults.
//
// A technique's folder is its CLI name, except where that cannot be:
//   --shadow none       techniques/none/
//   --oit none          techniques/opaque_hair/    (a second "none": opaque, depth-tested hair)
//   --oit occupancy     techniques/occupancy_oit/  (a second "occupancy": ordered blending)
//   --oit wsum, wavg    techniques/weighted/       (one class, two weightings)
// The ground-truth helpers shared by both kinds (fragment lists, peeling steps) are in
// techniques/common/.
#include "scenes/options.h"
#include "techniques/abuffer/abuffer.h"
#include "techniques/adsm/adsm.h"
#include "techniques/avsm/avsm.h"
#include "techniques/common/technique.h"
#include "techniques/dc/dc.h"
#include "techniques/dom/dom.h"
#include "techniques/dsm/dsm.h"
#include "techniques/dual_peel/dual_peel.h"
#include "techniques/exact/exact.h"
#include "techniques/fake/fake.h"
#include "techniques/fom/fom.h"
#include "techniques/kbuffer/kbuffer.h"
#include "techniques/mboit/mboit.h"
#include "techniques/mlab/mlab.h"
#include "techniques/msm/msm.h"
#include "techniques/none/none.h"
#include "techniques/occupancy/occupancy.h"
#include "techniques/occupancy_oit/occupancy_oit.h"
#include "techniques/opaque_hair/opaque_hair.h"
#include "techniques/osm/osm.h"
#include "techniques/peel/peel.h"
#include "techniques/peel_classic/peel_classic.h"
#include "techniques/shadowmap/shadowmap.h"
#include "techniques/shortcut/shortcut.h"
#include "techniques/stochastic/stochastic.h"
#include "techniques/voxel/voxel.h"
#include "techniques/wboit/wboit.h"
#include "techniques/weighted/weighted.h"

namespace sb {

namespace {

const TechniqueInfo& find(const std::vector<TechniqueInfo>& catalog, const Spec& spec,
                          const std::string& kind) {
  std::vector<std::string> names;
  for (const auto& t : catalog) {
    if (t.name == spec.name) return t;
    names.push_back(t.name);
  }
  throw InputError(unknownNameMessage(kind, spec.name, names));
}

uint32_t mapSize(const OptionReader& o) {
  return static_cast<uint32_t>(o.integer("size", 1, 16384));
}

}  // namespace

const std::vector<TechniqueInfo>& shadowCatalog() {
  static const std::vector<TechniqueInfo> catalog = {
      {"none", "no shadows: Kajiya-Kay shading with the light always visible", {}},
      {"shadowmap",
       "hard shadow map (Williams 1978) cast by the mesh and the hair onto both",
       {{"size", "512", "shadow map resolution (size x size), 1..16384"},
        {"bias", "0.002", "depth bias in light depth units [0,1], 0..1"}}},
      {"exact",
       "ground truth: (1-shadow_alpha)^n for the n hair fragments in front, per light texel",
       {{"method", "abuffer",
         "abuffer (sorted light-space fragment lists) | peel (depth peeling from the light); "
         "the tests prove them identical"},
        {"size", "512", "light map resolution (size x size), 1..16384"},
        {"bias", "0.002", "depth bias in light depth units [0,1], 0..1"},
        {"layers", "65536", "most layers peeled (a cap that is reported), 1..1000000"}}},
      {"occupancy",
       "occupancy maps (Sintorn & Assarsson 2009): depth range, 1 bit per slice, slab counts",
       {{"size", "512", "map resolution (size x size), 1..16384"},
        {"bias", "0.002", "depth bias in light depth units [0,1], 0..1"},
        {"slices", "128",
         "occupancy bits per texel, multiple of 32 (128 per RGBA32UI layer), 32..1024"},
        {"slabs", "4", "fragment counts per texel (4 per RGBA32F layer), dividing slices, 1..32"},
        {"slab_map", "on",
         "on | off (every set bit counts as one fragment; not the paper's) | count (the paper's "
         "occupancy-only variant: each set bit counts F/S, F the texel's fragment count, S its "
         "set bits; one count per texel)"},
        {"jitter", "off", "on | off: lookup jittered by up to half a texel (anti-aliasing)"},
        {"jitter_samples", "1", "jitter=on: jittered lookups averaged (the paper's use), 1..64"}}},
      {"dc",
       "density clustering (Mertens et al. 2004): per-texel k-means of fragment depths",
       {{"size", "512", "map resolution (size x size), 1..16384"},
        {"bias", "0.002", "depth bias in light depth units [0,1], 0..1"},
        {"clusters", "4", "depth clusters per texel (one channel each, 4 per layer), 1..8"},
        {"iterations", "2", "k-means iterations (passes over the hair), 1..64"}}},
      {"osm",
       "opacity shadow maps (Kim & Neumann 2001): planar opacity maps, linear interpolation",
       {{"maps", "16", "number of opacity maps, 1..512"},
        {"slicing", "uniform",
         "uniform | density (equal hair points per slice) | gamma (tighter near the light)"},
        {"gamma", "2", "slicing=gamma exponent: D_i = near + (far-near)(i/n)^gamma, 0.1..10"},
        {"passes", "multi",
         "single (one hair pass per map, the original) | multi (up to 6 targets x 4 maps a pass)"},
        {"bits", "32",
         "8 (RGBA8 unorm, kappa-scaled: the paper's limited-bit maps) | 16 (RGBA16F: half "
         "float counts, not kappa-scaled; exact to 2048 fragments) | 32 (RGBA32F)"},
        {"kappa", "0", "bits=8: e^-kappa at opacity 1; 0 derives 8 ln 2 (the paper), 0..100"},
        {"size", "512", "map resolution (size x size), 1..16384"},
        {"bias", "0.002", "depth bias in light depth units [0,1], 0..1"},
        {"filter", "none",
         "lookup kernel on the opacity (Unreal): none | pcf2x2 | pcf6x4 (3x3 pcf2x2, 2 apart) | "
         "pcf6x6 (36 texels) | box3x3 (the OSM paper's 3x3 average)"}}},
      {"dom",
       "deep opacity maps (Yuksel & Keyser 2008): layers that follow the hair from its first depth",
       {{"layers", "3", "opacity layers K, 1..31 (K = 4n-1 fills n RGBA layers of one array)"},
        {"spacing", "linear",
         "constant | linear | pow2 | fibonacci | list (layer sizes) | power (Unreal: K s "
         "(k/K)^2.8)"},
        {"list", "1;2;3",
         "spacing=list: layer sizes as multiples of the layer size, ';'-separated"},
        {"size_abs", "0", "layer size in light depth units (0: use size_frac), 0..1"},
        {"size_frac", "0.1", "layer size as a fraction of the hair's depth range from the light"},
        {"beyond", "last", "fragments beyond the last layer: ignore | last | extend"},
        {"depth_bits", "32",
         "precision of z0 (the depth-only pass's 32-bit float depth map), quantized "
         "where read: 8 | 16 | 32"},
        {"filter", "none",
         "lookup kernel on the opacity (Unreal): none | pcf2x2 | pcf6x4 (3x3 pcf2x2, 2 apart) | "
         "pcf6x6 (36 texels) | box3x3 (the OSM paper's 3x3 average)"},
        {"size", "512", "map resolution (size x size), 1..16384"},
        {"bias", "0.002", "depth bias in light depth units [0,1], 0..1"}}},
      {"dsm",
       "deep shadow maps (Lokovic & Veach 2000): per texel, the exact visibility compressed to a "
       "piecewise-linear curve within epsilon",
       {{"epsilon", "0.01", "greatest visibility error of the compression (0: exact), 0..1"},
        {"max_nodes", "64", "most nodes kept per texel (more are cut and reported), 2..65536"},
        {"size", "512", "map resolution (size x size), 1..16384"},
        {"bias", "0.002", "depth bias in light depth units [0,1], 0..1"}}},
      {"fom",
       "Fourier opacity maps (Jansen & Bavoil 2010): absorption as a Fourier series in depth, "
       "transmittance clamped to [0,1]",
       {{"coefficients", "8",
         "frequencies n (2n+1 floats per texel, 4 per RGBA32F layer, 8 layers a hair pass), 1..31"},
        {"size", "512", "map resolution (size x size), 1..16384"},
        {"bias", "0.002", "depth bias in light depth units [0,1], 0..1"}}},
      {"msm",
       "moment shadow maps for semi-transparent occluders (Muenstermann et al. 2018's shadow "
       "variant; Peters & Klein 2015): absorbance-weighted moments of light depth, mboit's "
       "reconstruction with the paper's bias",
       {{"moments", "6",
         "real moments beyond b0: 4 | 6 | 8 (kind=trig: 2, 3, 4 complex trigonometric moments)"},
        {"kind", "power", "power | trig: power moments of depth or trigonometric moments"},
        {"size", "512", "map resolution (size x size), 1..16384"},
        {"bias", "0.002", "depth bias in light depth units [0,1], 0..1"}}},
      {"adsm",
       "approximated deep shadows (TressFX, Tomb Raider 2013): one front-depth map, "
       "(1-alpha)^(dz/(spacing x radius) + 1), Gaussian PCF",
       {{"spacing", "4", "fiber spacing in fiber radii (radius: half the mean strand thickness)"},
        {"kernel", "5", "PCF taps per side, Gaussian weights sigma = kernel/2/2.4 (TressFX), 1..9"},
        {"size", "512", "map resolution (size x size), 1..16384"},
        {"bias", "0.002", "depth bias in light depth units [0,1], 0..1"}}},
      {"avsm",
       "adaptive volumetric shadow maps (Salvi et al. 2010): per texel a curve of at most `nodes` "
       "nodes, each fragment streamed in and the least-area node removed (timing emulated: "
       "resolve in primitive order)",
       {{"nodes", "8", "most nodes per texel curve: 4 | 8 | 16"},
        {"size", "512", "map resolution (size x size), 1..16384"},
        {"bias", "0.002", "depth bias in light depth units [0,1], 0..1"}}},
      {"voxel",
       "voxelized hair density (as Unreal ships it): fragment counts splatted into a volume of "
       "uint counters over the light's view, visibility exp(-density_scale w n), n the hair "
       "count marched to the light",
       {{"grid", "128", "slices over the hair's depth range, columns per side (<= size), 4..256"},
        {"steps", "128", "march steps over the hair's depth range from the light, 1..4096"},
        {"density_scale", "1", "scale of the marched hair count (1: w per fragment), 0..100"},
        {"size", "512", "resolution the hair is splatted at (size x size fragments), 1..16384"},
        {"bias", "0.002", "depth bias in light depth units [0,1], 0..1"}}},
  };
  return catalog;
}

std::unique_ptr<ShadowTechnique> makeShadowTechnique(const Spec& spec) {
  const TechniqueInfo& info = find(shadowCatalog(), spec, "shadow technique");
  const OptionReader o(spec, info.options, "shadow technique '" + spec.name + "'");
  const auto bias = [&] { return static_cast<float>(o.number("bias", 0.0, 1.0)); };
  if (spec.name == "shadowmap") return std::make_unique<ShadowMap>(mapSize(o), bias());
  if (spec.name == "occupancy")
    return std::make_unique<OccupancyShadow>(OccupancyShadow::readOptions(o));
  if (spec.name == "dc")
    return std::make_unique<DensityClusteringShadow>(DensityClusteringShadow::readOptions(o));
  if (spec.name == "osm")
    return std::make_unique<OpacityShadowMaps>(OpacityShadowMaps::readOptions(o));
  if (spec.name == "fom")
    return std::make_unique<FourierOpacityMaps>(FourierOpacityMaps::readOptions(o));
  if (spec.name == "msm")
    return std::make_unique<MomentShadowMaps>(MomentShadowMaps::readOptions(o));
  if (spec.name == "adsm")
    return std::make_unique<ApproximatedDeepShadows>(ApproximatedDeepShadows::readOptions(o));
  if (spec.name == "avsm")
    return std::make_unique<AdaptiveVolumetricShadowMaps>(
        AdaptiveVolumetricShadowMaps::readOptions(o));
  if (spec.name == "voxel")
    return std::make_unique<VoxelDensityShadow>(VoxelDensityShadow::readOptions(o));
  if (spec.name == "dsm") return std::make_unique<DeepShadowMaps>(DeepShadowMaps::readOptions(o));
  if (spec.name == "dom") return std::make_unique<DeepOpacityMaps>(DeepOpacityMaps::readOptions(o));
  if (spec.name == "exact")
    return std::make_unique<ExactShadow>(
        o.choice("method", {"peel", "abuffer"}) == "peel" ? ExactShadow::Method::Peel
                                                          : ExactShadow::Method::ABuffer,
        mapSize(o), bias(), static_cast<uint32_t>(o.integer("layers", 1, 1000000)));
  return std::make_unique<NoShadow>();
}

const std::vector<TechniqueInfo>& oitCatalog() {
  static const std::vector<TechniqueInfo> catalog = {
      {"none", "no transparency: opaque, depth-tested hair", {}},
      {"peel",
       "ground truth: depth peeling from the eye, front to back, every layer",
       {{"layers", "65536", "most layers peeled (a cap that is reported), 1..1000000"}}},
      {"abuffer",
       "ground truth cross-check: per-pixel fragment lists, sorted and composited",
       {{"max_fragments", "50000000", "most fragments stored (32 bytes each), 1..1000000000"}}},
      {"wsum",
       "weighted sum (Meshkin 2007; Bavoil & Myers 2008): C = sum(a c) + (1 - sum a) C_dst, "
       "saturated to [0,1]",
       {}},
      {"wavg",
       "weighted average (Bavoil & Myers 2008): avg colour sum(a c)/sum(a), T = (1 - sum(a)/n)^n",
       {}},
      {"wboit",
       "weighted blended OIT (McGuire & Bavoil 2013): depth-weighted average, exact coverage",
       {{"weight", "eq10",
         "const | eq7 | eq8 | eq9 | eq10: the paper's depth weight w(z, a) (eq10: window depth)"},
        {"precision", "32", "accumulation target bits: 16 (RGBA16F) | 32 (RGBA32F)"}}},
      {"occupancy",
       "occupancy-ordered blending (Sintorn & Assarsson 2009): order from eye-space occupancy maps",
       {{"slices", "128",
         "occupancy bits per pixel, multiple of 32 (128 per RGBA32UI layer), 32..1024"},
        {"slabs", "4", "fragment counts per pixel (4 per RGBA32F layer), dividing slices, 1..32"},
        {"lambda", "on",
         "on | off: renormalise the hair weights to 1 - prod(1 - alpha) (Lambda / hair.a: the "
         "printed hair.a / Lambda inverted, see README)"},
        {"order", "corrected",
         "corrected (the fragment's own share taken out, spread within its slice) | paper (the "
         "printed F_i / B_total * B_before)"}}},
      {"mboit",
       "moment-based OIT (Muenstermann et al. 2018): transmittance from power or "
       "trigonometric moments of log depth, the paper's bias; two hair passes",
       {{"moments", "6",
         "real moments beyond b0: 4 | 6 | 8 (kind=trig: 2, 3, 4 complex trigonometric moments)"},
        {"kind", "power", "power | trig: power moments of depth or trigonometric moments"},
        {"precision", "32",
         "moment target bits: 16 (RGBA16F, the paper's 16-bit bias) | 32 (RGBA32F)"}}},
      {"kbuffer",
       "k-buffer over per-pixel lists as TressFX 4 resolves them: the k nearest sorted, "
       "the rest blended as a tail",
       {{"k", "8", "fragments kept and sorted per pixel, 1..32"},
        {"nodes", "0",
         "node pool entries (32 bytes each); 0: the counted fragments; a full pool drops "
         "fragments (counted and reported), 0..1000000000"}}},
      {"mlab",
       "multi-layer alpha blending (Salvi & Vaidyanathan 2014); without fragment-shader "
       "interlock merged in primitive order in a resolve (timing marked emulated)",
       {{"layers", "4", "layers per pixel, 1..32"}}},
      {"shortcut",
       "TressFX ShortCut: the k nearest depths by atomic min, those fragments blended in order, "
       "the rest as a weighted average under the product of (1 - alpha)",
       {{"k", "3", "nearest fragments blended in order per pixel, 1..16"}}},
      {"stochastic",
       "stochastic transparency (Enderton et al. 2010): random sample masks, S sample depths "
       "per pixel, total alpha + depth + accumulate passes, alpha-corrected",
       {{"samples", "8", "samples per pixel S, 1..64 (one pass each, S depths per pixel)"},
        {"seed", "1", "random seed of the coverage masks, 0..4294967295"}}},
      {"peel_classic",
       "depth peeling as the papers time it (Everitt 2001): one geometry pass per layer, "
       "depth ties lost and counted",
       {{"layers", "65536", "most layers peeled (a cap that is reported), 1..1000000"}}},
      {"fake",
       "fake transparency (Yuksel & Keyser 2008, section 5): the strands in 3 interleaved "
       "subsets, each drawn opaque into its own image, the 3 images blended equally",
       {}},
      {"dual_peel",
       "dual depth peeling (Bavoil & Myers 2008): the nearest and farthest layers per pass, "
       "ceil(layers/2) peel passes after one min/max depth pass",
       {{"layers", "65536", "most layers peeled (a cap that is reported), 1..1000000"}}},
  };
  return catalog;
}

std::unique_ptr<OitTechnique> makeOitTechnique(const Spec& spec) {
  const TechniqueInfo& info = find(oitCatalog(), spec, "transparency technique");
  const OptionReader o(spec, info.options, "transparency technique '" + spec.name + "'");
  if (spec.name == "peel")
    return std::make_unique<PeelOit>(static_cast<uint32_t>(o.integer("layers", 1, 1000000)));
  if (spec.name == "occupancy") return std::make_unique<OccupancyOit>(OccupancyOit::readOptions(o));
  if (spec.name == "abuffer")
    return std::make_unique<ABufferOit>(
        static_cast<uint64_t>(o.integer("max_fragments", 1, 1000000000)));
  if (spec.name == "mboit") return std::make_unique<MomentOit>(MomentOit::readOptions(o));
  if (spec.name == "kbuffer") return std::make_unique<KBufferOit>(KBufferOit::readOptions(o));
  if (spec.name == "mlab")
    return std::make_unique<MlabOit>(static_cast<int>(o.integer("layers", 1, MlabOit::kMaxLayers)));
  if (spec.name == "shortcut")
    return std::make_unique<ShortCutOit>(static_cast<int>(o.integer("k", 1, ShortCutOit::kMaxK)));
  if (spec.name == "peel_classic")
    return std::make_unique<ClassicPeelOit>(static_cast<uint32_t>(o.integer("layers", 1, 1000000)));
  if (spec.name == "dual_peel")
    return std::make_unique<DualPeelOit>(static_cast<uint32_t>(o.integer("layers", 1, 1000000)));
  if (spec.name == "stochastic")
    return std::make_unique<StochasticOit>(StochasticOit::readOptions(o));
  if (spec.name == "fake") return std::make_unique<FakeTransparency>();
  if (spec.name == "wsum") return std::make_unique<WeightedOit>(WeightedOit::Mode::Sum);
  if (spec.name == "wavg") return std::make_unique<WeightedOit>(WeightedOit::Mode::Average);
  if (spec.name == "wboit")
    return std::make_unique<WeightedBlendedOit>(
        WeightedBlendedOit::weightFromName(
            o.choice("weight", {"const", "eq7", "eq8", "eq9", "eq10"})),
        o.choice("precision", {"16", "32"}) == "16" ? 16 : 32);
  return std::make_unique<OpaqueHair>();
}

}  // namespace sb
