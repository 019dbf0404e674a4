// The shadow techniques by name, with their options and defaults.
#include "scenes/options.h"
#include "techniques/common/technique.h"
#include "techniques/none/none.h"
#include "techniques/shadowmap/shadowmap.h"

namespace sb {

const std::vector<TechniqueInfo>& shadowCatalog() {
  static const std::vector<TechniqueInfo> catalog = {
      {"none", "no shadows: Kajiya-Kay shading with the light always visible", {}},
      {"shadowmap",
       "hard shadow map (Williams 1978) cast by the mesh and the hair onto both",
       {{"size", "512", "shadow map resolution (size x size), 1..16384"},
        {"bias", "0.002", "depth bias in light depth units [0,1], 0..1"}}},
  };
  return catalog;
}

std::unique_ptr<ShadowTechnique> makeShadowTechnique(const Spec& spec) {
  const auto& catalog = shadowCatalog();
  const TechniqueInfo* info = nullptr;
  std::vector<std::string> names;
  for (const auto& t : catalog) {
    names.push_back(t.name);
    if (t.name == spec.name) info = &t;
  }
  if (!info) throw InputError(unknownNameMessage("shadow technique", spec.name, names));
  const OptionReader opts(spec, info->options, "shadow technique '" + spec.name + "'");
  if (spec.name == "shadowmap")
    return std::make_unique<ShadowMap>(static_cast<uint32_t>(opts.integer("size", 1, 16384)),
                                       static_cast<float>(opts.number("bias", 0.0, 1.0)));
  return std::make_unique<NoShadow>();
}

}  // namespace sb
