#include "harness/reference_spec.h"

#include "base/errors.h"
#include "scenes/options.h"

namespace sb {

namespace {
constexpr int kMaxAaSamples = 8;
}  // namespace

const std::vector<ReferenceKind>& referenceCatalog() {
  static const std::vector<ReferenceKind> kinds = {
      {"exact",
       "the aliased exact reference: exact shadows and transparency at one sample per pixel "
       "(error.image, error.visibility, error.own)",
       {}},
      {"aa",
       "the anti-aliased exact reference: the same at samples x samples per pixel and per light "
       "texel, strands drawn with their true width, box-filtered (error.aa)",
       {{"samples",
         "4",
         "samples per pixel along each axis, 1..8",
         OptionKind::Integer,
         1,
         kMaxAaSamples,
         {}}}},
  };
  return kinds;
}

std::string ReferenceSpec::str() const {
  return name == "aa" ? "aa:samples=" + std::to_string(samples) : name;
}

ReferenceSpec parseReferenceSpec(const std::string& text) {
  const Spec spec = Spec::parse(text);
  std::vector<std::string> names;
  const ReferenceKind* kind = nullptr;
  for (const ReferenceKind& k : referenceCatalog()) {
    names.push_back(k.name);
    if (k.name == spec.name) kind = &k;
  }
  if (!kind) throw InputError(unknownNameMessage("reference", spec.name, names));
  const OptionReader o(spec, kind->options, "reference '" + spec.name + "'");
  ReferenceSpec r;
  r.name = spec.name;
  if (r.name == "aa") r.samples = static_cast<int>(o.integer("samples"));
  return r;
}

}  // namespace sb
