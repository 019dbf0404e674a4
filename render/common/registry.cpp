// The registry the technique folders fill (render/common/unit.h), and what
// is made from it: the factories by name and the option declarations.
#include <algorithm>
#include <iterator>
#include <map>

#include "render/common/unit.h"

namespace sb {

namespace {

// Filled during static initialisation, hence a function-local static.
std::map<std::string, TechniqueDescriptor>& registry(Family f) {
  static std::map<std::string, TechniqueDescriptor> families[3];
  return families[static_cast<int>(f)];
}

}  // namespace

const char* familyName(Family f) {
  switch (f) {
    case Family::Shadow:
      return "shadow";
    case Family::Transparency:
      return "transparency";
    case Family::Shading:
      break;
  }
  return "shading";
}

const char* familyFlag(Family f) { return f == Family::Transparency ? "oit" : familyName(f); }

TechniqueRegistrar::TechniqueRegistrar(TechniqueDescriptor d) {
  const Family f = d.family;
  const std::string name = d.name;
  if (!registry(f).emplace(name, std::move(d)).second)
    throw std::logic_error(std::string("two ") + familyName(f) + " techniques named " + name);
}

std::vector<const TechniqueDescriptor*> techniques(Family f) {
  std::vector<const TechniqueDescriptor*> out;
  for (const auto& [name, d] : registry(f)) out.push_back(&d);
  // The baseline first: the viewer starts there and `list` reads from it.
  std::stable_partition(out.begin(), out.end(),
                        [](const TechniqueDescriptor* d) { return d->name == "none"; });
  return out;
}

const TechniqueDescriptor* tryFindTechnique(Family f, const std::string& name) {
  const auto it = registry(f).find(name);
  return it == registry(f).end() ? nullptr : &it->second;
}

std::vector<std::string> techniqueNames(Family f, bool (*keep)(const TechniqueDescriptor&)) {
  std::vector<std::string> names;
  for (const TechniqueDescriptor* d : techniques(f))
    if (!keep || keep(*d)) names.push_back(d->name);
  return names;
}

const TechniqueDescriptor& defaultTechnique(Family f) {
  const TechniqueDescriptor* found = nullptr;
  for (const TechniqueDescriptor* d : techniques(f)) {
    if (!d->isDefault) continue;
    if (found)
      throw std::logic_error(std::string("two default ") + familyName(f) +
                             " techniques: " + found->name + ", " + d->name);
    found = d;
  }
  if (!found) throw std::logic_error(std::string("no default ") + familyName(f) + " technique");
  return *found;
}

const TechniqueDescriptor& findTechnique(Family f, const std::string& name) {
  if (const TechniqueDescriptor* d = tryFindTechnique(f, name)) return *d;
  std::vector<std::string> names;
  for (const TechniqueDescriptor* d : techniques(f)) names.push_back(d->name);
  const std::string kind = f == Family::Shading ? std::string("shading model")
                                                : std::string(familyName(f)) + " technique";
  throw InputError(unknownNameMessage(kind, name, names));
}

OptionReader readerFor(const TechniqueDescriptor& d, const Spec& spec) {
  const std::string what = d.family == Family::Shading
                               ? "shading model '" + d.name + "'"
                               : std::string(familyName(d.family)) + " technique '" + d.name + "'";
  return OptionReader(spec, d.options, what);
}

std::unique_ptr<ShadowTechnique> makeShadowTechnique(const Spec& spec) {
  const TechniqueDescriptor& d = findTechnique(Family::Shadow, spec.name);
  return d.makeShadow(readerFor(d, spec));
}

std::unique_ptr<OitTechnique> makeOitTechnique(const Spec& spec) {
  const TechniqueDescriptor& d = findTechnique(Family::Transparency, spec.name);
  return d.makeOit(readerFor(d, spec));
}

ShadingModel ShadingModel::fromSpec(const std::string& text) {
  const Spec spec = Spec::parse(text);
  const TechniqueDescriptor& d = findTechnique(Family::Shading, spec.name);
  ShadingModel m = d.makeShading(readerFor(d, spec));
  m.spec = text;
  m.shader = "techniques/" + d.folder + "/shading.glsl";  // every model's, by name
  return m;
}

void checkTechniqueSpec(Family f, const std::string& spec) {
  if (f == Family::Shading)
    ShadingModel::fromSpec(spec);
  else if (f == Family::Shadow)
    makeShadowTechnique(Spec::parse(spec));
  else
    makeOitTechnique(Spec::parse(spec));
}

// The capabilities the classes once declared themselves, now read from their descriptors.
bool ShadowTechnique::monotone() const {
  const TechniqueDescriptor* d = tryFindTechnique(Family::Shadow, name());
  return !d || d->caps.monotone;
}

bool OitTechnique::multisampled() const {
  const TechniqueDescriptor* d = tryFindTechnique(Family::Transparency, name());
  return d && d->caps.multisampling;
}

}  // namespace sb
