// --reference exact: the default reference, the run's exact shadows and transparency.
#include "render/common/unit.h"

#include "harness/reference_spec.h"
#include "harness/references/exact/exact_reference.h"

namespace sb {

const char* kReferenceOit = "abuffer";

Spec referenceShadowSpec(const Spec& shadow) {
  Spec ref;
  ref.name = "exact";
  ref.options["method"] = "abuffer";
  auto size = shadow.options.find("size");
  if (size != shadow.options.end()) ref.options["size"] = size->second;
  // A jittered lookup (occupancy's jitter=on) is judged against the exact maps looked up with
  // the same jitter: the same sampling of the light map, as the same size is.
  // Unjittered, the reference stays the one every other technique has ("exact", one key).
  if (auto it = shadow.options.find("jitter"); it != shadow.options.end() && it->second == "on") {
    ref.options["jitter"] = "on";
    if (auto n = shadow.options.find("jitter_samples"); n != shadow.options.end())
      ref.options["jitter_samples"] = n->second;
  }
  return ref;
}

namespace {
const OptionTable<ReferenceLightMap>& lightMapTable() {
  static const OptionTable<ReferenceLightMap> table(
      {opt::mapSize(&ReferenceLightMap::size), opt::bias(&ReferenceLightMap::bias)});
  return table;
}

struct ExactReference : Reference {
  std::string str() const override { return "exact"; }
};
}  // namespace

ReferenceLightMap referenceLightMap(const Spec& refShadow) {
  // The technique's reader: its declared defaults and ranges, whatever this table says.
  return lightMapTable().read(readerFor(findTechnique(Family::Shadow, refShadow.name), refShadow));
}

Spec withLightMapSize(const Spec& refShadow, uint32_t size) {
  Spec out = refShadow;
  out.options["size"] = std::to_string(size);
  return out;
}

}  // namespace sb

SB_REFERENCE({.name = "exact",
              .help = "the aliased exact reference: exact shadows and transparency at one "
                      "sample per pixel (error.image, error.visibility, error.own)",
              .options = {},
              .isDefault = true,
              .make = [](const sb::OptionReader&) {
                return std::make_shared<const ExactReference>();
              }});
