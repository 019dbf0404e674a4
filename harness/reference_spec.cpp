// The registry the reference folders fill (harness/reference_spec.h) and the specs read
// through it.
#include "harness/reference_spec.h"

#include <algorithm>
#include <map>
#include <stdexcept>

#include "base/errors.h"
#include "base/unit_folder.h"

namespace sb {

namespace {

// Filled during static initialisation, hence a function-local static.
std::map<std::string, ReferenceDescriptor>& registry() {
  static std::map<std::string, ReferenceDescriptor> references;
  return references;
}

}  // namespace

RenderResult::MoreReference Reference::render(const ReferenceInputs&) const {
  throw std::logic_error("reference " + str() + " is the run's own: it renders with the run");
}

ReferenceRegistrar::ReferenceRegistrar(const char* file, ReferenceDescriptor d) {
  d.folder = unitFolder(file, "harness/references/", "reference");
  if (d.name.empty() || d.help.empty() || !d.make)
    throw std::logic_error(std::string(file) + ": a reference needs a name, help and make");
  const std::string name = d.name;
  if (!registry().emplace(name, std::move(d)).second)
    throw std::logic_error("two references named " + name);
}

std::vector<const ReferenceDescriptor*> referenceCatalog() {
  std::vector<const ReferenceDescriptor*> out;
  for (const auto& [name, d] : registry()) out.push_back(&d);
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
