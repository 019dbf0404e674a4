// What `strandbench list` prints about techniques, generated from their
// descriptors (render/common/unit.h): text, JSON and the Markdown of
// docs/techniques.md (`strandbench list --markdown`).
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "harness/settings.h"
#include "render/common/unit.h"

namespace sb {

// "Shadow techniques", "Transparency techniques", "Hair shading models".
const char* heading(Family f);
// A typed option's valid values: "1..16384", "on | off", "" (text).
std::string optionRange(const OptionInfo& o, const char* choiceSeparator = " | ");
nlohmann::json optionsJson(const std::vector<OptionInfo>& options);
nlohmann::json techniqueJson(const TechniqueDescriptor& d);
// "  name  help" and one line per option; `detailed` adds paper, folder,
// capabilities and each option's type and range (`list NAME`).
void printTechnique(std::ostream& out, const TechniqueDescriptor& d, bool detailed);
// The capabilities as words ("multisampling, exact"), "-" when none.
std::string capabilitiesText(const TechniqueDescriptor& d);
std::string techniquesMarkdown();
// A spec other than the default, for help texts and the settings' examples: the first
// technique by name with an option, that option at its default ("adsm:size=512").
std::string exampleSpec(Family f);
// The request's shadow, oit and shading specs checked against the registry, a
// message led by the setting (suites, manifests and render requests alike).
void checkTechniqueSpecs(const RenderRequest& r, Spelling spelling);

}  // namespace sb
