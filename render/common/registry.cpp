// The registry the technique folders fill (render/common/unit.h), and what
// is made from it: the factories by name and the option declarations.
#include <algorithm>
#include <iterator>
#include <nlohmann/json.hpp>

#include "base/unit_registry.h"
#include "render/common/shader_library.h"
#include "render/common/unit.h"

namespace sb {

namespace {

// One registry per family: a shadow and a transparency technique may share a name ("none").
UnitRegistry<TechniqueDescriptor>& registry(Family f) {
  static UnitRegistry<TechniqueDescriptor> families[3] = {{"shadow technique", "techniques/"},
                                                          {"transparency technique", "techniques/"},
                                                          {"shading model", "techniques/"}};
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

namespace {

// A unit.json key's value as T, or `fallback` where it is absent.
template <class T>
T value(const nlohmann::json& j, const char* key, T fallback, const std::string& where) {
  if (!j.contains(key)) return fallback;
  try {
    return j.at(key).get<T>();
  } catch (const nlohmann::json::exception&) {
    throw std::logic_error(where + ": \"" + key + "\" has the wrong type");
  }
}

// Every key of `j` is one of `known`: a misspelt key is an error, not a silent default.
void onlyKeys(const nlohmann::json& j, std::initializer_list<const char*> known,
              const std::string& where) {
  for (const auto& [key, v] : j.items())
    if (std::find_if(known.begin(), known.end(), [&](const char* k) { return key == k; }) ==
        known.end())
      throw std::logic_error(where + ": unknown key \"" + key + "\"");
}

}  // namespace

void describeUnit(TechniqueDescriptor& d, const std::string& path, const std::string& text) {
  const nlohmann::json units = nlohmann::json::parse(text, nullptr, false);
  if (!units.is_object() || units.empty())
    throw std::logic_error(path + ": not a JSON object of technique names");
  if (d.name.empty()) {
    if (units.size() != 1)
      throw std::logic_error(path + ": several techniques; unit.cpp names the one it registers");
    d.name = units.begin().key();
  }
  const std::string where = path + ": " + d.name;
  if (!units.contains(d.name) || !units[d.name].is_object())
    throw std::logic_error(where + " is not described");
  const nlohmann::json& u = units[d.name];
  onlyKeys(u, {"paper", "help", "capabilities", "stepped", "default", "note"}, where);
  if (!u.contains("paper") || !u.contains("help"))
    throw std::logic_error(where + ": \"paper\" and \"help\" are required");
  d.paper = value<std::string>(u, "paper", "", where);
  d.help = value<std::string>(u, "help", "", where);
  d.isDefault = value<bool>(u, "default", false, where);
  const nlohmann::json caps =
      value<nlohmann::json>(u, "capabilities", nlohmann::json::object(), where);
  onlyKeys(caps,
           {"multisampling", "interlock", "emulated_timing", "monotone", "exact", "msaa_refusal",
            "mesh_refusal"},
           where + " capabilities");
  d.caps.multisampling = value<bool>(caps, "multisampling", false, where);
  d.caps.interlock = value<bool>(caps, "interlock", false, where);
  d.caps.emulatedTiming = value<bool>(caps, "emulated_timing", false, where);
  d.caps.monotone = value<bool>(caps, "monotone", true, where);
  d.caps.exact = value<bool>(caps, "exact", false, where);
  d.caps.msaaRefusal = value<std::string>(caps, "msaa_refusal", "", where);
  d.caps.meshRefusal = value<std::string>(caps, "mesh_refusal", "", where);
  if (u.contains("stepped")) {
    const nlohmann::json& s = u["stepped"];
    onlyKeys(s, {"option", "doubling", "min", "max"}, where + " stepped");
    d.stepped = SteppedOption{
        value<std::string>(s, "option", "", where), value<bool>(s, "doubling", false, where),
        value<long long>(s, "min", 0, where), value<long long>(s, "max", 0, where)};
  }
}

TechniqueRegistrar::TechniqueRegistrar(const char* file, TechniqueDescriptor d) {
  d.family = d.makeShading ? Family::Shading : d.makeOit ? Family::Transparency : Family::Shadow;
  d.folder = registry(d.family).folderOf(file);  // its unit.json describes it (and names it)
  const std::string path = "techniques/" + d.folder + "/unit.json";
  const auto json = embeddedShaders().find(path);
  if (json == embeddedShaders().end()) throw std::logic_error(path + " is missing");
  describeUnit(d, path, json->second);
  registry(d.family).add(file, std::move(d));
}

std::vector<const TechniqueDescriptor*> techniques(Family f) {
  std::vector<const TechniqueDescriptor*> out = registry(f).all();
  // The baseline first: the viewer starts there and `list` reads from it.
  std::stable_partition(out.begin(), out.end(),
                        [](const TechniqueDescriptor* d) { return d->name == "none"; });
  return out;
}

const TechniqueDescriptor* tryFindTechnique(Family f, const std::string& name) {
  return registry(f).find(name);
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
  throw InputError(unknownNameMessage(registry(f).kind(), name, techniqueNames(f)));
}

OptionReader readerFor(const TechniqueDescriptor& d, const Spec& spec) {
  return OptionReader(spec, d.options, registry(d.family).kind() + " '" + d.name + "'");
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
