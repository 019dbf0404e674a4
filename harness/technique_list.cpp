#include "harness/technique_list.h"

#include <cmath>
#include <sstream>

namespace sb {

namespace {

constexpr Family kFamilies[] = {Family::Shadow, Family::Transparency, Family::Shading};

std::string number(double v) {
  if (v == std::floor(v) && std::fabs(v) < 1e15) return std::to_string(static_cast<long long>(v));
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string joined(const std::vector<std::string>& v, const char* sep) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

// Markdown table cells hold no '|' of their own.
std::string cell(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

const char* heading(Family f) {
  return f == Family::Shadow         ? "Shadow techniques"
         : f == Family::Transparency ? "Transparency techniques"
                                     : "Hair shading models";
}

std::string optionRange(const OptionInfo& o, const char* choiceSeparator) {
  switch (o.kind) {
    case OptionKind::Integer:
    case OptionKind::Number:
      return number(o.min) + ".." + number(o.max);
    case OptionKind::Choice:
    case OptionKind::Flag:
      return joined(o.choices, choiceSeparator);
    case OptionKind::Text:
      break;
  }
  return "";
}

nlohmann::json optionsJson(const std::vector<OptionInfo>& options) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& o : options) {
    nlohmann::json j = {{"name", o.name},
                        {"default", o.defaultValue},
                        {"help", o.help},
                        {"kind", optionKindName(o.kind)}};
    if (o.kind == OptionKind::Integer) {
      j["min"] = static_cast<long long>(o.min);
      j["max"] = static_cast<long long>(o.max);
    } else if (o.kind == OptionKind::Number) {
      j["min"] = o.min;
      j["max"] = o.max;
    } else if (!o.choices.empty()) {
      j["choices"] = o.choices;
    }
    a.push_back(j);
  }
  return a;
}

std::string exampleSpec(Family f) {
  for (const TechniqueDescriptor* d : techniques(f))
    if (!d->isDefault && !d->options.empty())
      return d->name + ":" + d->options.front().name + "=" + d->options.front().defaultValue;
  return defaultTechnique(f).name;
}

std::string capabilitiesText(const TechniqueDescriptor& d) {
  std::vector<std::string> c;
  if (d.caps.multisampling) c.push_back("multisampling");
  if (d.caps.interlock) c.push_back("needs interlock");
  if (d.caps.emulatedTiming) c.push_back("emulated timing");
  if (d.family == Family::Shadow && !d.caps.monotone) c.push_back("not monotone");
  if (d.caps.exact) c.push_back("exact");
  return c.empty() ? "-" : joined(c, ", ");
}

nlohmann::json techniqueJson(const TechniqueDescriptor& d) {
  nlohmann::json j = {{"name", d.name},
                      {"help", d.help},
                      {"options", optionsJson(d.options)},
                      {"family", familyName(d.family)},
                      {"folder", "techniques/" + d.folder},
                      {"paper", d.paper},
                      {"capabilities",
                       {{"multisampling", d.caps.multisampling},
                        {"interlock", d.caps.interlock},
                        {"emulated_timing", d.caps.emulatedTiming},
                        {"monotone", d.caps.monotone},
                        {"exact", d.caps.exact},
                        {"msaa_refusal", d.caps.msaaRefusal}}}};
  if (d.stepped)
    j["stepped"] = {{"option", d.stepped->option},
                    {"doubling", d.stepped->doubling},
                    {"min", d.stepped->min},
                    {"max", d.stepped->max}};
  return j;
}

void printTechnique(std::ostream& out, const TechniqueDescriptor& d, bool detailed) {
  out << "  " << d.name << "  " << d.help << "\n";
  if (detailed) {
    out << "    family: " << familyName(d.family) << " (--" << familyFlag(d.family) << " " << d.name
        << "), folder: techniques/" << d.folder << "/\n";
    if (!d.paper.empty()) out << "    paper: " << d.paper << "\n";
    out << "    capabilities: " << capabilitiesText(d) << "\n";
    if (!d.caps.msaaRefusal.empty()) out << "    --msaa: refused: " << d.caps.msaaRefusal << "\n";
    if (d.stepped)
      out << "    viewer steps: " << d.stepped->option << (d.stepped->doubling ? " x2" : " +1")
          << " in " << d.stepped->min << ".." << d.stepped->max << "\n";
  }
  for (const auto& o : d.options) {
    out << "      " << o.name << "=" << o.defaultValue << "  " << o.help;
    if (detailed) {
      const std::string range = optionRange(o);
      out << "  [" << optionKindName(o.kind) << (range.empty() ? "" : " " + range) << "]";
    }
    out << "\n";
  }
}

std::string techniquesMarkdown() {
  std::ostringstream md;
  md << "# Techniques\n\n"
     << "Generated from the techniques' descriptors (each folder's `unit.cpp`) by\n"
     << "`strandbench list --markdown > docs/techniques.md`; a test fails when this file is "
        "stale.\n";
  for (Family f : kFamilies) {
    md << "\n## " << heading(f) << " (`--" << familyFlag(f) << " NAME:key=value,...`)\n\n"
       << "| name | folder | paper | capabilities | options (default, range) |\n"
       << "|---|---|---|---|---|\n";
    for (const TechniqueDescriptor* d : techniques(f)) {
      std::vector<std::string> opts;
      for (const auto& o : d->options) {
        const std::string range = optionRange(o);
        opts.push_back("`" + o.name + "=" + o.defaultValue + "`" +
                       (range.empty() ? "" : " (" + range + ")") +
                       (d->stepped && d->stepped->option == o.name ? " stepped" : ""));
      }
      md << "| `" << d->name << "` | `techniques/" << d->folder << "/` | "
         << cell(d->paper.empty() ? "-" : d->paper) << " | " << capabilitiesText(*d) << " | "
         << cell(opts.empty() ? "-" : joined(opts, "<br>")) << " |\n";
    }
  }
  return md.str();
}

void checkTechniqueSpecs(const RenderRequest& r, Spelling spelling) {
  for (Family f : kFamilies) {
    const Setting& setting = *findSetting(familyFlag(f));
    const std::string text = settingText(r, setting);
    try {
      checkTechniqueSpec(f, text);
    } catch (const InputError& e) {
      throw InputError(settingMessage(setting, spelling, text, e.what()));
    }
  }
}

}  // namespace sb
