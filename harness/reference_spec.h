// The references a render is compared with (`--reference [SPEC]`, the suite key
// "reference"), each a unit as techniques are: a folder harness/references/<name>/ whose
// unit.cpp registers it (SB_REFERENCE, below) with its name, help, typed options
// (an OptionTable bound to its own struct) and factory. Nothing central lists them:
// referenceCatalog(), the settings' help and the specs' checks read this registry. The
// default (isDefault) is rendered with the run itself (harness/render_measures.cpp); the
// others render on their own (Reference::render) and are compared with the image
// (moreReferences, harness/render_references.cpp), each writing its own slice of
// error.<name> (ReferenceSlice).
#pragma once

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/options.h"
#include "base/unit_registry.h"
#include "harness/render.h"

namespace sb {

// What a reference renders from: the run's request, scene and settings and its exact shadow
// (harness/references/exact/exact_reference.h: the default reference's, whose light map the
// others scale or trace).
struct ReferenceInputs {
  const RenderRequest& req;
  const Scene& scene;
  const RenderSettings& settings;
  const Spec& refShadow;
};

// A reference's own part of its result (what only it measures, kept with the result in the
// sweep's cache), and its fields in error.<name> beside the core ones.
class ReferenceSlice {
 public:
  virtual ~ReferenceSlice() = default;
  // Adds its fields to `e` (error.<name>), after the comparison filled m's core fields.
  virtual void json(const RenderResult::MoreReference& m, nlohmann::json& e) const = 0;
};

// One spec of a reference, its options read into the unit's own struct.
class Reference {
 public:
  virtual ~Reference() = default;
  // Canonical text: "exact", "aa:samples=4", "pbr:mode=path,spp=16,...".
  virtual std::string str() const = 0;
  // Refuses (InputError) what cannot be made at any memory, before any work.
  virtual void check(const RenderSettings& /*settings*/, const Spec& /*refShadow*/) const {}
  // The reference image and its cost (the core fields but the comparison's, and its slice).
  // The default reference has none of its own: it is the run's (throws std::logic_error).
  virtual RenderResult::MoreReference render(const ReferenceInputs& in) const;
};

// unit.cpp gives name, help, options and make; the registrar fills `folder` from where
// unit.cpp is.
struct ReferenceDescriptor {
  std::string name;  // --reference NAME[:options], error.NAME
  std::string help;
  std::string example;  // a cheap valid spec (the settings' example); "": the name
  std::vector<OptionInfo> options;
  bool isDefault = false;  // rendered whenever any reference is
  std::string folder;      // harness/references/<folder>/
  // From a reader made with `options` (every value already checked).
  std::function<std::shared_ptr<const Reference>(const OptionReader&)> make;
};

struct ReferenceRegistrar {
  ReferenceRegistrar(const char* file, ReferenceDescriptor d);
};

// A reference's folder registers it from its unit.cpp, at file scope:
//   SB_REFERENCE({.name = "aa", .help = "...", .options = kTable.infos(), .make = ...});
#define SB_REFERENCE(...) SB_REGISTER(ReferenceRegistrar, __VA_ARGS__)

// Every reference, the default first, then by name.
std::vector<const ReferenceDescriptor*> referenceCatalog();
const ReferenceDescriptor& defaultReference();

// A parsed spec: the unit's name and its options read.
struct ReferenceSpec {
  std::string name;
  std::shared_ptr<const Reference> unit;
  std::string str() const { return unit ? unit->str() : name; }
  bool operator==(const ReferenceSpec& o) const { return str() == o.str(); }
};

// Throws InputError ("reference 'aa': option samples=9 is out of range [1, 8]")
// for a malformed spec, an unknown name, an unknown option or a value out of range.
ReferenceSpec parseReferenceSpec(const std::string& text);

}  // namespace sb
