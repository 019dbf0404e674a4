// The techniques as self-describing units (render/common/unit.h): every
// descriptor is complete, its options drive validation, and what is generated
// from the registry (list, docs/techniques.md) and the catalog (baselines, the
// quick suite, the error and memory scripts) covers every registered technique.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "harness/baselines.h"
#include "harness/reference_spec.h"
#include "harness/suite.h"
#include "harness/technique_list.h"
#include "render/common/unit.h"
#include "test_util.h"

namespace {

namespace fs = std::filesystem;
using sb::Family;
using sb::TechniqueDescriptor;

constexpr Family kTechniqueFamilies[] = {Family::Shadow, Family::Transparency};

std::vector<const TechniqueDescriptor*> all() {
  std::vector<const TechniqueDescriptor*> out;
  for (Family f : {Family::Shadow, Family::Transparency, Family::Shading})
    for (const auto* d : sb::techniques(f)) out.push_back(d);
  return out;
}

std::string what(const TechniqueDescriptor& d) {
  return std::string(sb::familyFlag(d.family)) + " " + d.name;
}

TEST(TechniqueUnits, EveryDescriptorIsComplete) {
  EXPECT_GE(sb::techniques(Family::Shadow).size(), 13u);
  EXPECT_GE(sb::techniques(Family::Transparency).size(), 15u);
  EXPECT_EQ(sb::techniques(Family::Shading).size(), 4u);
  for (const TechniqueDescriptor* d : all()) {
    SCOPED_TRACE(what(*d));
    EXPECT_FALSE(d->help.empty());
    EXPECT_TRUE(fs::is_directory(fs::path(SB_SOURCE_DIR) / "techniques" / d->folder));
    EXPECT_EQ(d->makeShadow != nullptr, d->family == Family::Shadow);
    EXPECT_EQ(d->makeOit != nullptr, d->family == Family::Transparency);
    EXPECT_EQ(d->makeShading != nullptr, d->family == Family::Shading);
    // Every default is valid, and the factory builds the technique it names.
    EXPECT_NO_THROW(sb::checkTechniqueSpec(d->family, d->name));
    if (d->family == Family::Shadow) {
      const auto t = sb::makeShadowTechnique(sb::Spec::parse(d->name));
      EXPECT_EQ(t->name(), d->name);
      EXPECT_EQ(t->monotone(), d->caps.monotone);
    } else if (d->family == Family::Transparency) {
      const auto t = sb::makeOitTechnique(sb::Spec::parse(d->name));
      EXPECT_EQ(t->name(), d->name);
      EXPECT_EQ(t->multisampled(), d->caps.multisampling);
    }
    for (const auto& o : d->options) {
      EXPECT_FALSE(o.help.empty()) << o.name;
      if (o.kind == sb::OptionKind::Integer || o.kind == sb::OptionKind::Number) {
        EXPECT_LT(o.min, o.max) << o.name;
      }
      if (o.kind == sb::OptionKind::Choice) {
        EXPECT_GE(o.choices.size(), 2u) << o.name;
      }
    }
    if (d->stepped) {
      const auto o =
          std::find_if(d->options.begin(), d->options.end(),
                       [&](const sb::OptionInfo& x) { return x.name == d->stepped->option; });
      ASSERT_NE(o, d->options.end()) << d->stepped->option;
      EXPECT_EQ(o->kind, sb::OptionKind::Integer);
      EXPECT_GE(d->stepped->min, static_cast<long long>(o->min));
      EXPECT_LE(d->stepped->max, static_cast<long long>(o->max));
    }
  }
}

// Each folder's unit.json describes the techniques its unit.cpp registers, and no others.
TEST(TechniqueUnits, EveryUnitJsonEntryIsRegistered) {
  std::set<std::string> registered, described;
  for (const TechniqueDescriptor* d : all()) registered.insert(d->folder + "/" + d->name);
  for (const auto& e : fs::directory_iterator(fs::path(SB_SOURCE_DIR) / "techniques")) {
    const fs::path file = e.path() / "unit.json";
    ASSERT_TRUE(fs::is_regular_file(file)) << file;
    const nlohmann::json units = nlohmann::json::parse(sbtest::readFile(file));
    for (const auto& [name, v] : units.items())
      described.insert(e.path().filename().string() + "/" + name);
  }
  EXPECT_EQ(described, registered);
}

// describeUnit fills a descriptor from unit.json and names the file and key it refuses.
TEST(TechniqueUnits, UnitJsonIsChecked) {
  auto describe = [](const std::string& text, std::string name = "") {
    TechniqueDescriptor d;
    d.name = std::move(name);
    sb::describeUnit(d, "techniques/x/unit.json", text);
    return d;
  };
  const TechniqueDescriptor d = describe(
      R"({"x": {"paper": "P 2000", "help": "h", "default": true,
                "stepped": {"option": "size", "doubling": true, "min": 16, "max": 4096},
                "capabilities": {"monotone": false, "msaa_refusal": "why"}}})");
  EXPECT_EQ(d.name, "x");
  EXPECT_EQ(d.paper, "P 2000");
  EXPECT_EQ(d.help, "h");
  EXPECT_TRUE(d.isDefault);
  ASSERT_TRUE(d.stepped.has_value());
  EXPECT_EQ(d.stepped->option, "size");
  EXPECT_TRUE(d.stepped->doubling);
  EXPECT_EQ(d.stepped->max, 4096);
  EXPECT_FALSE(d.caps.monotone);
  EXPECT_FALSE(d.caps.multisampling);
  EXPECT_EQ(d.caps.msaaRefusal, "why");
  EXPECT_EQ(
      describe(R"({"a": {"paper": "", "help": "a"}, "b": {"paper": "", "help": "b"}})", "b").help,
      "b");
  auto refused = [&](const std::string& text, const std::string& name = "") {
    try {
      describe(text, name);
    } catch (const std::logic_error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refused(R"({"x": {"paper": "", "hlep": "h"}})"),
            "techniques/x/unit.json: x: unknown key \"hlep\"");
  EXPECT_EQ(refused(R"({"x": {"help": "h"}})"),
            "techniques/x/unit.json: x: \"paper\" and \"help\" are required");
  EXPECT_EQ(refused(R"({"x": {"paper": "", "help": "h", "capabilities": {"exact": "yes"}}})"),
            "techniques/x/unit.json: x: \"exact\" has the wrong type");
  EXPECT_EQ(refused(R"({"a": {"paper": "", "help": "a"}, "b": {"paper": "", "help": "b"}})"),
            "techniques/x/unit.json: several techniques; unit.cpp names the one it registers");
  EXPECT_EQ(refused(R"({"a": {"paper": "", "help": "a"}})", "b"),
            "techniques/x/unit.json: b is not described");
  EXPECT_EQ(refused("{not json"), "techniques/x/unit.json: not a JSON object of technique names");
}

TEST(TechniqueUnits, TypedOptionsRefuseWithTheClosestName) {
  auto message = [](const std::string& spec) {
    try {
      sb::makeShadowTechnique(sb::Spec::parse(spec));
    } catch (const sb::InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("dom:layres=3").find("did you mean 'layers'"), std::string::npos);
  EXPECT_NE(message("dom:spacing=liner").find("did you mean 'linear'"), std::string::npos);
  EXPECT_NE(message("dom:layers=40").find("out of range [1, 31]"), std::string::npos);
  EXPECT_NE(message("occupancy:jitter=yes").find("not one of on off"), std::string::npos);
  EXPECT_NE(message("shadowmpa").find("did you mean 'shadowmap'"), std::string::npos);
}

TEST(TechniqueUnits, ListShowsOneTechniqueAndTypedJson) {
  const auto one = sbtest::runCli("list dom");
  ASSERT_EQ(one.status, 0) << one.err;
  for (const char* part : {"dom", "Yuksel & Keyser 2008", "layers=3", "[integer 1..31]",
                           "spacing=linear", "viewer steps: layers"})
    EXPECT_NE(one.out.find(part), std::string::npos) << part << " in\n" << one.out;
  EXPECT_EQ(one.out.find("shadowmap"), std::string::npos) << one.out;
  const auto bad = sbtest::runCli("list doom");
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.err.find("did you mean 'dom'"), std::string::npos) << bad.err;

  const auto j = nlohmann::json::parse(sbtest::runCli("list --json").out);
  for (const char* key : {"shadow", "oit", "shading"}) {
    ASSERT_TRUE(j.contains(key)) << key;
    for (const auto& t : j[key])
      for (const char* field : {"name", "help", "options"}) EXPECT_TRUE(t.contains(field));
  }
  const auto dom = std::find_if(j["shadow"].begin(), j["shadow"].end(),
                                [](const auto& t) { return t["name"] == "dom"; });
  ASSERT_NE(dom, j["shadow"].end());
  const auto& layers = (*dom)["options"][0];
  EXPECT_EQ(layers["name"], "layers");
  EXPECT_EQ(layers["kind"], "integer");
  EXPECT_EQ(layers["default"], "3");
  EXPECT_EQ(layers["min"], 1);
  EXPECT_EQ(layers["max"], 31);
}

// docs/techniques.md is generated; regenerate it with the command in the message.
TEST(TechniqueUnits, DocsTableIsFresh) {
  const std::string doc = sbtest::readFile(fs::path(SB_SOURCE_DIR) / "docs" / "techniques.md");
  EXPECT_EQ(doc, sb::techniquesMarkdown())
      << "docs/techniques.md is stale: regenerate it with "
         "`build/strandbench list --markdown > docs/techniques.md`";
  const auto cli = sbtest::runCli("list --markdown");
  EXPECT_EQ(cli.status, 0);
  EXPECT_EQ(cli.out, sb::techniquesMarkdown());
}

// The catalog, driven by the registry: every shadow and transparency technique
// has a committed baseline on both backends (which `strandbench check` also
// compares GL against Vulkan: the parity check) and a case in the quick suite.
TEST(TechniqueUnits, EveryTechniqueHasABaselineParityAndAQuickCase) {
  const sb::Manifest m = sb::loadManifest(fs::path(SB_SOURCE_DIR) / "baselines" / "manifest.json");
  const sb::Suite quick = sb::loadSuite(std::string(SB_SOURCE_DIR) + "/suites/quick.json");
  for (Family f : kTechniqueFamilies)
    for (const TechniqueDescriptor* d : sb::techniques(f)) {
      SCOPED_TRACE(what(*d));
      auto uses = [&](const sb::RenderRequest& r) {
        return sb::Spec::parse(f == Family::Shadow ? r.shadow : r.oit).name == d->name;
      };
      bool parity = false;
      for (const auto& c : m.cases)
        if (uses(c.request)) {
          const auto& b = c.backends;
          parity |=
              std::count(b.begin(), b.end(), "gl") && std::count(b.begin(), b.end(), "vulkan");
        }
      EXPECT_TRUE(parity) << "no baseline case on gl and vulkan in baselines/manifest.json";
      EXPECT_TRUE(std::any_of(quick.cases.begin(), quick.cases.end(), [&](const sb::SweepCase& c) {
        return uses(c.request);
      })) << "no case in suites/quick.json";
    }
}

// The error and memory tables' scripts take their techniques from the registry.
TEST(TechniqueUnits, TableScriptsReadTheRegistry) {
  for (const char* script : {"shadow-errors.sh", "oit-errors.sh", "memory-table.sh"}) {
    const std::string text = sbtest::readFile(fs::path(SB_SOURCE_DIR) / "scripts" / script);
    EXPECT_NE(text.find("list --json"), std::string::npos) << script;
  }
}

// ---- A technique's CLI name lives in its folder (issue: "nothing central lists techniques").

// The string literals of C++ or GLSL source, comments left out.
std::vector<std::string> stringLiterals(const std::string& src) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < src.size(); ++i) {
    if (src.compare(i, 2, "//") == 0) {
      i = src.find('\n', i);
      if (i == std::string::npos) break;
    } else if (src.compare(i, 2, "/*") == 0) {
      i = src.find("*/", i + 2);
      if (i == std::string::npos) break;
      ++i;
    } else if (src[i] == '\'') {  // a char literal ('"' included)
      i = src.find('\'', src[i + 1] == '\\' ? i + 3 : i + 2);
      if (i == std::string::npos) break;
    } else if (src[i] == '"') {
      std::string lit;
      for (++i; i < src.size() && src[i] != '"' && src[i] != '\n'; ++i) {
        if (src[i] == '\\' && i + 1 < src.size()) lit += src[i++];
        lit += src[i];
      }
      out.push_back(lit);
    }
  }
  return out;
}

bool namesWord(const std::string& text, const std::string& name) {
  auto part = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  };
  for (std::size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + 1))
    if ((at == 0 || !part(text[at - 1])) &&
        (at + name.size() == text.size() || !part(text[at + name.size()])))
      return true;
  return false;
}

// "file: name (literal)" for each C++ or GLSL file under `root` (outside tests/, fuzz/ and the
// build) with a string literal naming one of `names` where `allowed(file, name)` is false.
// withIncludes false: #include lines (paths) are not read.
std::vector<std::string> namesInLiterals(
    const fs::path& root, const std::set<std::string>& names,
    const std::function<bool(const std::string&, const std::string&)>& allowed,
    bool withIncludes = true) {
  std::vector<std::string> found;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const std::string ext = entry.path().extension().string();
    if (!entry.is_regular_file() ||
        !(ext == ".cpp" || ext == ".h" || ext == ".glsl" || ext == ".vert" || ext == ".frag" ||
          ext == ".comp" || ext == ".mesh"))
      continue;
    const std::string rel = fs::relative(entry.path(), root).generic_string();
    if (rel.rfind("tests/", 0) == 0 || rel.rfind("build", 0) == 0 || rel.rfind("fuzz/", 0) == 0)
      continue;
    std::string src = sbtest::readFile(entry.path());
    if (!withIncludes) src = std::regex_replace(src, std::regex(R"(#\s*include[^\n]*)"), "");
    const std::vector<std::string> literals = stringLiterals(src);
    for (const std::string& name : names) {
      if (allowed(rel, name)) continue;
      for (const std::string& lit : literals)
        if (namesWord(lit, name)) {
          found.push_back(rel + ": " + name + " (\"" + lit + "\")");
          break;
        }
    }
  }
  return found;
}

// "file: name" for each string literal under `root` (C++ and GLSL, outside tests/)
// that names a registered technique outside its own folder, except what the issue
// allows: the references (exact, peel, abuffer) anywhere, the paper benchmarks and
// figures, and the code reused by design (listed here, and in docs/layout.md).
std::vector<std::string> namesOutsideFolders(const fs::path& root) {
  const std::set<std::string> references = {"exact", "peel", "abuffer"};
  const std::set<std::string> papers = {"cli/bench_command.cpp", "cli/figure_command.cpp"};
  const std::map<std::string, std::set<std::string>> reuse = {
      {"techniques/msm/", {"mboit"}},                // MSM is MBOIT's moment math on light maps
      {"techniques/occupancy_oit/", {"occupancy"}},  // the occupancy maps' transparency order
      {"techniques/rt_oit/", {"kbuffer"}}};          // k=: the k-buffer's merge of the hits past k
  // A name's folders: two descriptors may share one (occupancy: shadow and transparency).
  std::map<std::string, std::set<std::string>> homes;
  std::set<std::string> names;
  for (const TechniqueDescriptor* d : all()) {
    homes[d->name].insert("techniques/" + d->folder + "/");
    names.insert(d->name);
  }
  return namesInLiterals(root, names, [&](const std::string& rel, const std::string& name) {
    // "none" (the default shadow and transparency) is also the word for absence.
    bool allowed = papers.count(rel) > 0 || references.count(name) > 0 || name == "none";
    for (const std::string& home : homes.at(name)) allowed = allowed || rel.rfind(home, 0) == 0;
    for (const auto& [prefix, reused] : reuse)
      allowed = allowed || (rel.rfind(prefix, 0) == 0 && reused.count(name));
    return allowed;
  });
}

TEST(TechniqueUnits, NoFileOutsideAFolderNamesItsTechnique) {
  const std::vector<std::string> found = namesOutsideFolders(SB_SOURCE_DIR);
  std::string list;
  for (const auto& f : found) list += "\n  " + f;
  EXPECT_TRUE(found.empty()) << "technique names outside their folders:" << list;
}

// "file: name" for each string literal under `root` (C++ and GLSL, outside tests/, #include
// lines aside: a path) that names a registered reference outside its own folder
// (harness/references/<folder>/). The default reference (exact) is the exact techniques'
// (exact shadows with abuffer transparency), whose names the check above allows anywhere;
// pbr/ is the pbr reference's physics, named for it.
std::vector<std::string> referenceNamesOutsideFolders(const fs::path& root) {
  std::map<std::string, std::string> homes;  // name: its folder
  std::set<std::string> names;
  for (const sb::ReferenceDescriptor* d : sb::referenceCatalog())
    if (!d->isDefault) {
      homes[d->name] = "harness/references/" + d->folder + "/";
      names.insert(d->name);
    }
  const std::map<std::string, std::string> reuse = {{"pbr/", "pbr"}};
  return namesInLiterals(
      root, names,
      [&](const std::string& rel, const std::string& name) {
        if (rel.rfind(homes.at(name), 0) == 0) return true;
        for (const auto& [prefix, n] : reuse)
          if (rel.rfind(prefix, 0) == 0 && n == name) return true;
        return false;
      },
      false);
}

TEST(ReferenceUnits, NoFileOutsideAFolderNamesItsReference) {
  const std::vector<std::string> found = referenceNamesOutsideFolders(SB_SOURCE_DIR);
  std::string list;
  for (const auto& f : found) list += "\n  " + f;
  EXPECT_TRUE(found.empty()) << "reference names outside their folders:" << list;
}

TEST(ReferenceUnits, NamesOutsideFoldersAreFound) {
  // The control: a reference's name planted in a string outside its folder is found; in a
  // comment, an #include, its own folder or (pbr) the pbr/ library it is not.
  const fs::path root = sbtest::tempDir("reference-names");
  for (const char* d : {"harness", "harness/references/aa", "pbr"})
    fs::create_directories(root / d);
  std::ofstream(root / "harness" / "x.cpp") << "#include \"pbr/hair_bsdf.h\"\n"
                                               "// \"aa\" in a comment\n"
                                               "const char* s = \"--reference aa:samples=2\";\n";
  std::ofstream(root / "harness" / "y.cpp") << "const char* ok = \"aab\";\n";
  std::ofstream(root / "harness" / "references" / "aa" / "z.cpp") << "const char* n = \"aa\";\n";
  std::ofstream(root / "pbr" / "w.cpp") << "const char* n = \"pbr reference\";\n";
  const std::vector<std::string> found = referenceNamesOutsideFolders(root);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].rfind("harness/x.cpp: aa", 0), 0u) << found[0];
  // Every reference is a unit in its own folder, the default (exact) among them.
  ASSERT_FALSE(sb::referenceCatalog().empty());
  EXPECT_TRUE(sb::referenceCatalog().front()->isDefault);
  for (const sb::ReferenceDescriptor* d : sb::referenceCatalog()) {
    EXPECT_EQ(d->folder, d->name);
    EXPECT_TRUE(
        fs::exists(fs::path(SB_SOURCE_DIR) / "harness" / "references" / d->folder / "unit.cpp"))
        << d->name;
  }
}

TEST(TechniqueUnits, NamesOutsideFoldersAreFound) {
  // The check itself: a name in a string is found, in a comment is not, in its folder is not.
  const fs::path root = sbtest::tempDir("names-outside");
  fs::create_directories(root / "harness");
  fs::create_directories(root / "techniques" / "dom");
  std::ofstream(root / "harness" / "x.cpp") << "// \"dom\" in a comment\n"
                                               "const char* c = '\"';\n"
                                               "const char* s = \"--shadow dom:layers=4\";\n";
  std::ofstream(root / "harness" / "y.cpp") << "/* \"osm\" */ const char* ok = \"domain\";\n";
  std::ofstream(root / "techniques" / "dom" / "z.cpp") << "const char* n = \"dom\";\n";
  const std::vector<std::string> found = namesOutsideFolders(root);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].rfind("harness/x.cpp: dom", 0), 0u) << found[0];
}

// "file: line" for each read of an option by its name under `root`, in techniques/ and the
// references' code in harness/ (harness/*reference*): a reader's method called with a string, a
// reader (a parameter `const OptionReader& r`) used for anything but handing it on, or a
// readOptions. Every option is declared once in an OptionTable bound to its struct member
// (base/options.h), and the struct is what the code reads.
std::vector<std::string> optionReadsByName(const fs::path& root) {
  static const std::regex literalRead(R"(\.\s*(number|integer|choice|flag|text|has)\s*\(\s*")");
  static const std::regex readerParam(R"(OptionReader\s*&\s*(\w+))");
  std::vector<std::string> found;
  auto scan = [&](const fs::path& file) {
    const std::string rel = fs::relative(file, root).generic_string();
    std::string src = sbtest::readFile(file);
    // Comments say what the code does; they are not reads.
    src = std::regex_replace(src, std::regex(R"(//[^\n]*)"), "");
    std::set<std::string> readers;
    for (std::sregex_iterator it(src.begin(), src.end(), readerParam), end; it != end; ++it)
      readers.insert((*it)[1]);
    std::istringstream lines(src);
    std::string line;
    for (int n = 1; std::getline(lines, line); ++n) {
      bool bad =
          std::regex_search(line, literalRead) || line.find("readOptions") != std::string::npos;
      for (const std::string& r : readers)
        bad = bad || std::regex_search(line, std::regex("\\b" + r + R"(\s*\.\s*\w+\s*\()"));
      if (bad) found.push_back(rel + ":" + std::to_string(n) + ": " + line);
    }
  };
  auto source = [](const fs::path& p) {
    const std::string ext = p.extension().string();
    return ext == ".cpp" || ext == ".h";
  };
  if (fs::is_directory(root / "techniques"))
    for (const auto& e : fs::recursive_directory_iterator(root / "techniques"))
      if (e.is_regular_file() && source(e.path())) scan(e.path());
  // The references' code in the harness: reference_spec.*, render_references.cpp and every
  // reference unit's folder (harness/references/).
  if (fs::is_directory(root / "harness"))
    for (const auto& e : fs::directory_iterator(root / "harness"))
      if (e.is_regular_file() && source(e.path()) &&
          e.path().filename().string().find("reference") != std::string::npos)
        scan(e.path());
  if (fs::is_directory(root / "harness" / "references"))
    for (const auto& e : fs::recursive_directory_iterator(root / "harness" / "references"))
      if (e.is_regular_file() && source(e.path())) scan(e.path());
  std::sort(found.begin(), found.end());
  return found;
}

// The folders under `root`/techniques that are no registered unit's (infrastructure
// lives in render/), and any loose file there.
std::vector<std::string> foldersNotUnits(const fs::path& root) {
  std::set<std::string> units;
  for (const TechniqueDescriptor* d : all()) units.insert(d->folder);
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(root / "techniques"))
    if (!e.is_directory() || !units.count(e.path().filename().string()))
      found.push_back("techniques/" + e.path().filename().string());
  std::sort(found.begin(), found.end());
  return found;
}

TEST(TechniqueUnits, NoOptionIsReadByName) {
  const std::vector<std::string> found = optionReadsByName(SB_SOURCE_DIR);
  std::string list;
  for (const auto& f : found) list += "\n  " + f;
  EXPECT_TRUE(found.empty()) << "options read by name, not through their OptionTable:" << list;
}

TEST(TechniqueUnits, OptionReadsByNameAreFound) {
  // The control: a copy of a technique's unit.cpp and of the references passes, and fails
  // with a read by name planted in each (a shadow, a shading model, a reference, the pbr
  // reference's harness code).
  const fs::path root = sbtest::tempDir("option-reads");
  const fs::path src(SB_SOURCE_DIR);
  for (const char* f : {"techniques/shadowmap/unit.cpp", "techniques/kajiya_kay/unit.cpp",
                        "harness/reference_spec.cpp", "harness/references/pbr/unit.cpp",
                        "harness/references/pbr/pbr_reference.cpp"}) {
    fs::create_directories((root / f).parent_path());
    fs::copy_file(src / f, root / f, fs::copy_options::overwrite_existing);
  }
  EXPECT_TRUE(optionReadsByName(root).empty());
  std::ofstream(root / "techniques" / "shadowmap" / "unit.cpp", std::ios::app)
      << "float planted(const sb::OptionReader& o) { return o.number(\"bias\"); }\n";
  std::ofstream(root / "techniques" / "kajiya_kay" / "unit.cpp", std::ios::app)
      << "float planted2(const OptionReader& reader, const char* n) { return "
         "float(reader.number(n)); }\n";
  std::ofstream(root / "harness" / "reference_spec.cpp", std::ios::app)
      << "// o.integer(\"samples\") in a comment is not a read\n"
         "int planted3(const sb::OptionReader& x);\n"
         "int planted4(const Reader& o) { return int(o.integer(\"samples\")); }\n";
  // As pbr_reference.cpp read the exact shadow's bias before it went through its table.
  std::ofstream(root / "harness" / "references" / "pbr" / "pbr_reference.cpp", std::ios::app)
      << "double planted5(const Spec& s) { return readerFor(findTechnique(Family::Shadow, "
         "s.name), s).number(\"bias\"); }\n";
  const std::vector<std::string> found = optionReadsByName(root);
  ASSERT_EQ(found.size(), 4u);
  EXPECT_EQ(found[0].rfind("harness/reference_spec.cpp:", 0), 0u) << found[0];
  EXPECT_NE(found[0].find("o.integer(\"samples\")"), std::string::npos) << found[0];
  EXPECT_EQ(found[1].rfind("harness/references/pbr/pbr_reference.cpp:", 0), 0u) << found[1];
  EXPECT_NE(found[1].find(".number(\"bias\")"), std::string::npos) << found[1];
  EXPECT_EQ(found[2].rfind("techniques/kajiya_kay/unit.cpp:", 0), 0u) << found[2];
  EXPECT_EQ(found[3].rfind("techniques/shadowmap/unit.cpp:", 0), 0u) << found[3];
}

TEST(TechniqueUnits, TechniquesHoldsUnitFoldersOnly) {
  const std::vector<std::string> found = foldersNotUnits(SB_SOURCE_DIR);
  std::string list;
  for (const auto& f : found) list += "\n  " + f;
  EXPECT_TRUE(found.empty()) << "not a unit's folder (shared code goes in render/):" << list;
  // The check itself: an infrastructure folder or a loose file is found, a unit's folder is not.
  const fs::path root = sbtest::tempDir("units-only");
  fs::create_directories(root / "techniques" / "dom");
  fs::create_directories(root / "techniques" / "common");
  std::ofstream(root / "techniques" / "loose.h") << "\n";
  EXPECT_EQ(foldersNotUnits(root),
            (std::vector<std::string>{"techniques/common", "techniques/loose.h"}));
}

// A shading model is its folder: its shading.glsl (bound as <shading>) and its own uniform
// block (uniforms.h, at SB_SLOT_SHADING_MODEL), and its CPU form; the shared shading code
// (render/shading/, render/common/shading_uniforms.h) names no model.
TEST(TechniqueUnits, ShadingModelsAreTheirFolders) {
  const fs::path root = SB_SOURCE_DIR;
  std::vector<std::string> words;
  for (const TechniqueDescriptor* d : sb::techniques(Family::Shading)) {
    SCOPED_TRACE(what(*d));
    const fs::path folder = root / "techniques" / d->folder;
    EXPECT_TRUE(fs::is_regular_file(folder / "shading.glsl"));
    const std::string block = sbtest::readFile(folder / "uniforms.h");
    EXPECT_NE(block.find("SB_SLOT_SHADING_MODEL"), std::string::npos);
    const sb::ShadingModel m = sb::ShadingModel::fromSpec(d->name);
    EXPECT_EQ(m.shader, "techniques/" + d->folder + "/shading.glsl");
    EXPECT_FALSE(m.params.empty());
    EXPECT_EQ(m.params.size() % 16, 0u);  // a std140 block's size
    ASSERT_TRUE(m.direct != nullptr);
    const glm::vec3 v = m.direct({0, 1, 0}, {0.6f, 0.8f, 0}, {0.8f, -0.6f, 0}, glm::vec3(0.5f));
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(std::isfinite(v[c]) && v[c] >= 0 && v[c] <= m.maxDirect) << v[c];
    }
    words.push_back(d->name);
    words.push_back(d->folder);
  }
  std::vector<fs::path> shared = {root / "render" / "common" / "shading_uniforms.h"};
  for (const auto& e : fs::directory_iterator(root / "render" / "shading"))
    shared.push_back(e.path());
  for (const fs::path& f : shared) {
    const std::string text = sbtest::readFile(f);
    for (const std::string& w : words)
      EXPECT_FALSE(namesWord(text, w)) << f.filename() << " names " << w;
  }
  // The control: a model's own file names it.
  EXPECT_TRUE(namesWord(sbtest::readFile(root / "techniques" / "sadeghi" / "unit.cpp"), "sadeghi"));
}

}  // namespace
