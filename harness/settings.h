// The settings of a render request (RenderRequest) as one table, read by every
// front end: the CLI options of render, probe and the benchmarks, the keys of
// suites (defaults, presets, groups, axes) and of the baselines manifest. Each
// entry parses its command-line text and its JSON value into the same field and
// checks the same range, so a setting means the same thing everywhere; the
// README's and docs/suites-and-results.md's settings table is settingsMarkdown().
//
// Messages name a setting as its front end spells it: "--size 0x0: ..." on the
// command line, "\"size\" '0x0': ..." in a suite or manifest.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "harness/render.h"

namespace sb {

enum class SettingType {
  Spec,  // NAME:key=value,... (scene and technique specs)
  String,
  Enum,        // one of `choices`
  Int,         // in [min, max]
  Float,       // finite, in the range of min / max (open or closed ends)
  Vec3,        // "x,y,z"; in JSON also [x, y, z]
  Flag,        // a CLI flag; a JSON bool
  Size,        // "WxH"; in JSON also a number N for NxN
  Probe,       // "X,Y[,MAP_SIZE[,SAMPLES]]"; in JSON also {"texel": [x, y], "map_size", "samples"}
  Animation,   // "KIND[:frames=N,degrees=D]"; in JSON also {"kind", "frames", "degrees"}
  Lights,      // "TYPE:X,Y,Z[:R,G,B[:INTENSITY]];..."; in JSON also a list of those or of
               // {"type", "position" | "direction", "color", "intensity"}
  References,  // the references compared with: "true" (the default, exact), "false", or specs
               // "exact;aa:samples=4"; on the CLI a flag that may take a spec, given more
               // than once; in JSON also true, false, a spec or a list of specs
};

struct Setting {
  std::string key;   // suites and manifests: "camera_eye"
  std::string flag;  // the CLI: "--camera-eye"; a flag that clears the setting: "--no-image"
  SettingType type = SettingType::String;
  std::vector<std::string> choices;  // Enum
  double min = 0, max = 0;           // Int, Float: the range when hasMin / hasMax
  bool hasMin = false, hasMax = false;
  bool minOpen = false, maxOpen = false;  // Float: ends excluded
  bool nonZero = false;                   // Vec3: the zero vector is refused
  std::string defaultText;                // as documented ("fitted to the scene", "512x512")
  std::string help;
  std::string example;     // a valid value other than the default (text form; tests, docs)
  std::string badExample;  // a value every front end refuses (text form; tests)
  // The setting's value in a request (canonical JSON; null when unset: fitted,
  // or the backend's default platform) and how a canonical value is stored.
  std::function<nlohmann::ordered_json(const RenderRequest&)> get;
  std::function<void(RenderRequest&, const nlohmann::ordered_json&)> set;

  std::string typeName() const;
  std::string rangeText() const;  // "1..16384", "(0, 180)", "lines, ribbons"; "" for none
};

const std::vector<Setting>& settingsTable();
// By JSON key; nullptr when there is none.
const Setting* findSetting(const std::string& key);
std::vector<std::string> settingKeys();
// The camera and light settings, camera_eye to extra_lights in table order: a
// render's view, which the benchmarks and the viewer take whole.
std::vector<std::string> viewSettingKeys();

// How a front end spells settings in messages.
enum class Spelling { Cli, Json };

// Sets one setting from its command-line text; throws InputError
// "<flag> <text>: <problem>".
void setFromText(RenderRequest& req, const Setting& s, const std::string& text);
// Sets one setting from a suite's or manifest's JSON value; throws InputError
// "\"<key>\" <value>: <problem>".
void setFromJson(RenderRequest& req, const Setting& s, const nlohmann::ordered_json& value);
// The value of a setting in `req` as its CLI text ("" when unset).
std::string settingText(const RenderRequest& req, const Setting& s);

// Every setting's range, then the rules between settings: the platform is one of
// the backend's, no image needs a reference, invariants need a reference. Throws
// InputError spelled for the front end. Technique and scene names are checked
// where the scene is built (checkRenderRequest, the suite parser).
void checkRequest(const RenderRequest& req, Spelling spelling);

// How a front end names a setting: "--size" or "\"size\"".
std::string settingLabel(const Setting& s, Spelling spelling);
// A message about a setting's value as the front end spells it:
// "--size 0x0: <problem>" or "\"size\" '0x0': <problem>".
std::string settingMessage(const Setting& s, Spelling spelling, const std::string& text,
                           const std::string& problem);

// A suite's or manifest's "backends": a non-empty list of distinct backend
// names. Throws InputError "\"backends\" ...".
std::vector<std::string> parseBackendList(const nlohmann::ordered_json& value);

// The command-line options of `keys` (all settings when empty), added to `cmd`;
// apply() sets the given ones into a request after parsing and checks it.
class CliSettings {
 public:
  // `defaults` is shown as each option's default in --help.
  CliSettings(CLI::App& cmd, const std::vector<std::string>& keys, const RenderRequest& defaults);
  // Sets every option given on the command line, in table order, then checkRequest.
  void apply(RenderRequest& req) const;

 private:
  struct Entry {
    const Setting* setting;
    CLI::Option* option;
    std::shared_ptr<std::string> text;
    std::shared_ptr<bool> flag;
    std::shared_ptr<std::vector<std::string>> texts;  // References: one per occurrence
  };
  std::vector<Entry> entries_;
};

// The settings table as Markdown (docs/suites-and-results.md and the README hold it)
// and as plain text and JSON for `strandbench list`.
std::string settingsMarkdown();
std::string settingsText();
nlohmann::json settingsJson();

}  // namespace sb
