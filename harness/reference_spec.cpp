// The registry the reference folders fill (harness/reference_spec.h) and the specs read
// through it.
#include "harness/reference_spec.h"

#include <algorithm>
#include <stdexcept>

#include "base/errors.h"
#include "base/unit_registry.h"

namespace sb {

namespace {

UnitRegistry<ReferenceDescriptor>& registry() {
  static UnitRegistry<ReferenceDescriptor> references("reference", "harness/references/");
  return references;
}

}  // namespace

RenderResult::MoreReference Reference::render(const ReferenceInputs&) const {
  throw std::logic_error("reference " + str() + " is the run's own: it renders with the run");
}

ReferenceRegistrar::ReferenceRegistrar(const char* file, ReferenceDescriptor d) {
  if (d.help.empty() || !d.make)
    throw std::logic_error(std::string(file) + ": a reference needs a name, help and make");
  registry().add(file, std::move(d));
}

std::vector<const ReferenceDescriptor*> referenceCatalog() {
  std::vector<const ReferenceDescriptor*> out = registry().all();
  std::stable_partition(out.begin(), out.end(),
                        [](const ReferenceDescriptor* d) { return d->isDefault; });
  return out;
}

const ReferenceDescriptor& defaultReference() {
  const std::vector<const ReferenceDescriptor*> all = referenceCatalog();
  if (all.empty() || !all.front()->isDefault || (all.size() > 1 && all[1]->isDefault))
    throw std::logic_error("not one default reference");
  return *all.front();
}

ReferenceSpec parseReferenceSpec(const std::string& text) {
  const Spec spec = Spec::parse(text);
  std::vector<std::string> names;
  const ReferenceDescriptor* kind = nullptr;
  for (const ReferenceDescriptor* d : referenceCatalog()) {
    names.push_back(d->name);
    if (d->name == spec.name) kind = d;
  }
  if (!kind) throw InputError(unknownNameMessage("reference", spec.name, names));
  return {kind->name,
          kind->make(OptionReader(spec, kind->options, "reference '" + spec.name + "'"))};
}

}  // namespace sb
