// The shadow and transparency techniques by name, with their options and defaults.
#include "scenes/options.h"
#include "techniques/abuffer/abuffer.h"
#include "techniques/common/technique.h"
#include "techniques/exact/exact.h"
#include "techniques/none/none.h"
#include "techniques/opaque_hair/opaque_hair.h"
#include "techniques/peel/peel.h"
#include "techniques/shadowmap/shadowmap.h"

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
  };
  return catalog;
}

std::unique_ptr<ShadowTechnique> makeShadowTechnique(const Spec& spec) {
  const TechniqueInfo& info = find(shadowCatalog(), spec, "shadow technique");
  const OptionReader o(spec, info.options, "shadow technique '" + spec.name + "'");
  const auto bias = [&] { return static_cast<float>(o.number("bias", 0.0, 1.0)); };
  if (spec.name == "shadowmap") return std::make_unique<ShadowMap>(mapSize(o), bias());
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
  };
  return catalog;
}

std::unique_ptr<OitTechnique> makeOitTechnique(const Spec& spec) {
  const TechniqueInfo& info = find(oitCatalog(), spec, "transparency technique");
  const OptionReader o(spec, info.options, "transparency technique '" + spec.name + "'");
  if (spec.name == "peel")
    return std::make_unique<PeelOit>(static_cast<uint32_t>(o.integer("layers", 1, 1000000)));
  if (spec.name == "abuffer")
    return std::make_unique<ABufferOit>(
        static_cast<uint64_t>(o.integer("max_fragments", 1, 1000000000)));
  return std::make_unique<OpaqueHair>();
}

}  // namespace sb
