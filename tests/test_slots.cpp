// Binding numbers are named once, for the C++ and the GLSL: the shared ones in
// render/common/slots.h, a folder's own in techniques/<folder>/slots.h. No
// shader under techniques/ spells a binding as a number, every SB_SLOT_ name a
// file uses is defined once, in the common header or its own folder's (and a
// shader includes that header itself), every header is plain #defines both
// languages read under its own include guard, a shader that includes a header
// twice still compiles, and no two names bound in one shader (with each shadow
// lookup in place of <shadow>) share a number. The scanners are functions,
// shown to catch a bad line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "backends/vulkan/vk_shader.h"
#include "render/common/shader_library.h"
#include "render/common/technique.h"
#include "render/common/unit.h"
#include "render/outputs/probe/slots.h"
#include "techniques/occupancy_oit/slots.h"

namespace {

namespace fs = std::filesystem;

const fs::path kSource = SB_SOURCE_DIR;
const std::string kCommonHeader = "render/common/slots.h";

std::string readText(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

// "file:line: text" for every binding given as a number (`binding = 3`, `binding=3`,
// `SB_UNIFORM_BLOCK(Name, 3)`: render/common/uniform_block.h).
std::vector<std::string> numericBindings(const std::string& file, const std::string& text) {
  static const std::regex numeric(R"((\bbinding\s*=|\bSB_UNIFORM_BLOCK\(\s*\w+\s*,)\s*[0-9])");
  std::vector<std::string> found;
  const auto lines = splitLines(text);
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (std::regex_search(lines[i], numeric))
      found.push_back(file + ":" + std::to_string(i + 1) + ": " + lines[i]);
  return found;
}

// name -> "file:line" of its first use, for every SB_SLOT_ name in text.
std::map<std::string, std::string> slotNamesUsed(const std::string& file, const std::string& text) {
  static const std::regex name(R"(\bSB_SLOT_\w+)");
  std::map<std::string, std::string> used;
  const auto lines = splitLines(text);
  for (std::size_t i = 0; i < lines.size(); ++i)
    for (std::sregex_iterator it(lines[i].begin(), lines[i].end(), name), end; it != end; ++it)
      used.emplace(it->str(), file + ":" + std::to_string(i + 1));
  return used;
}

// The slots a header defines: `#define SB_SLOT_NAME <number>` lines.
std::map<std::string, int> slotDefines(const std::string& header) {
  static const std::regex define(R"(^#define (SB_SLOT_\w+) ([0-9]+)\b)");
  std::map<std::string, int> defs;
  for (const auto& l : splitLines(header)) {
    std::smatch m;
    if (std::regex_search(l, m, define)) defs[m[1]] = std::stoi(m[2]);
  }
  return defs;
}

// The slots headers a file includes, "techniques/..." paths: a quoted #include
// resolved as the shader library does (next to the file) or, for the C++, from
// the source root.
std::set<std::string> includedSlotsHeaders(const std::string& file, const std::string& text) {
  static const std::regex include(R"re(^\s*#\s*include\s*"(([^"]*/)?slots\.h)")re");
  std::set<std::string> found;
  for (const auto& l : splitLines(text)) {
    std::smatch m;
    if (!std::regex_search(l, m, include)) continue;
    found.insert((fs::path(file).parent_path() / m.str(1)).lexically_normal().generic_string());
    found.insert(fs::path(m.str(1)).lexically_normal().generic_string());
  }
  return found;
}

// The names a (loaded) shader binds: `binding = SB_SLOT_NAME`, and a uniform
// block's `SB_UNIFORM_BLOCK(Name, SB_SLOT_NAME)` (render/common/uniform_block.h).
std::set<std::string> boundNames(const std::string& text) {
  static const std::regex bound(
      R"((?:\bbinding\s*=|\bSB_UNIFORM_BLOCK\(\s*\w+\s*,)\s*(SB_SLOT_\w+))");
  std::set<std::string> names;
  for (std::sregex_iterator it(text.begin(), text.end(), bound), end; it != end; ++it)
    names.insert(it->str(1));
  return names;
}

// "A and B at N" for every two names that share a number.
std::vector<std::string> collisions(const std::set<std::string>& names,
                                    const std::map<std::string, int>& numbers) {
  std::map<int, std::string> first;
  std::vector<std::string> found;
  for (const auto& n : names) {
    const auto it = numbers.find(n);
    if (it == numbers.end()) continue;  // undefined: EveryNameAFileUses... reports it
    const auto [at, fresh] = first.emplace(it->second, n);
    if (!fresh) found.push_back(at->second + " and " + n + " at " + std::to_string(it->second));
  }
  return found;
}

// techniques/<folder>/file or render/.../<folder>/file -> its folder, from the source root
std::string folderOf(const std::string& path) {
  return fs::path(path.substr(0, path.find(':'))).parent_path().generic_string();
}

// The expected include guard of a header: SB_SLOTS_H, or SB_<FOLDER>_SLOTS_H.
std::string guardOf(const std::string& header) {
  if (header == kCommonHeader) return "SB_SLOTS_H";
  std::string folder = fs::path(folderOf(header)).filename().string();
  std::transform(folder.begin(), folder.end(), folder.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return "SB_" + folder + "_SLOTS_H";
}

// Every file under techniques/ and render/ for which keep(path) holds, as paths from the
// source root.
template <class Keep>
std::vector<std::string> sourceFiles(Keep keep) {
  std::vector<std::string> files;
  for (const char* root : {"techniques", "render"})
    for (const auto& e : fs::recursive_directory_iterator(kSource / root))
      if (e.is_regular_file() && keep(e.path()))
        files.push_back(fs::relative(e.path(), kSource).generic_string());
  std::sort(files.begin(), files.end());
  return files;
}

// Every slots header, paths from the source root: the common one first, then each
// folder's own.
std::vector<std::string> slotHeaders() {
  std::vector<std::string> headers =
      sourceFiles([](const fs::path& p) { return p.filename() == "slots.h"; });
  std::stable_partition(headers.begin(), headers.end(),
                        [](const std::string& h) { return h == kCommonHeader; });
  return headers;
}

struct Slots {
  std::map<std::string, int> number;          // name -> its number
  std::map<std::string, std::string> header;  // name -> the header that defines it
  std::vector<std::string> twice;             // "NAME: a and b"
};

Slots allSlots() {
  Slots s;
  for (const auto& h : slotHeaders())
    for (const auto& [name, n] : slotDefines(readText(kSource / h))) {
      const auto [at, fresh] = s.header.emplace(name, h);
      if (!fresh) s.twice.push_back(name + ": " + at->second + " and " + h);
      s.number.emplace(name, n);
    }
  return s;
}

// Every shader source under techniques/ and render/.
std::vector<std::string> shaderFiles() {
  return sourceFiles([](const fs::path& p) {
    const std::string ext = p.extension().string();
    return ext == ".glsl" || ext == ".vert" || ext == ".frag" || ext == ".comp" || ext == ".mesh";
  });
}

// Every C++ file under techniques/ and render/ but the slots headers.
std::vector<std::string> cppFiles() {
  return sourceFiles([](const fs::path& p) {
    const std::string ext = p.extension().string();
    return (ext == ".cpp" || ext == ".h") && p.filename() != "slots.h";
  });
}

TEST(Slots, TheScannersCatchANumericBindingAndAnUnknownName) {
  const std::string bad =
      "// binding 3 in a comment is fine\n"
      "layout(std430, binding = 3) buffer X { uint x[]; };\n"
      "layout(binding = SB_SLOT_VIEW) uniform sampler2D a;\n"
      "layout(std140, binding=12) uniform Y { vec4 y; };\n"
      "layout(std430, binding = COUNTS_BINDING) buffer Z { uint z[]; };\n"
      "layout(binding = SB_SLOT_NO_SUCH_THING) uniform sampler2D b;\n"
      "SB_UNIFORM_BLOCK(W, 5)\n";
  EXPECT_EQ(numericBindings("techniques/x/bad.frag", bad),
            (std::vector<std::string>{
                "techniques/x/bad.frag:2: layout(std430, binding = 3) buffer X { uint x[]; };",
                "techniques/x/bad.frag:4: layout(std140, binding=12) uniform Y { vec4 y; };",
                "techniques/x/bad.frag:7: SB_UNIFORM_BLOCK(W, 5)"}));
  const auto used = slotNamesUsed("techniques/x/bad.frag", bad);
  EXPECT_EQ(used.size(), 2u);
  EXPECT_EQ(used.at("SB_SLOT_NO_SUCH_THING"), "techniques/x/bad.frag:6");
  const auto defs = slotDefines("#define SB_SLOT_VIEW 0\n#define SB_SLOTS_H\n");
  EXPECT_EQ(defs, (std::map<std::string, int>{{"SB_SLOT_VIEW", 0}}));
  EXPECT_FALSE(defs.count("SB_SLOT_NO_SUCH_THING"));
  EXPECT_TRUE(includedSlotsHeaders("techniques/x/bad.frag", bad).empty());
  EXPECT_EQ(includedSlotsHeaders("techniques/x/a.frag",
                                 "#include \"render/common/slots.h\"\n"
                                 "  #include \"slots.h\"\n")
                .count("techniques/x/slots.h"),
            1u);
  EXPECT_EQ(includedSlotsHeaders("techniques/x/a.frag", "#include \"render/common/slots.h\"\n")
                .count(kCommonHeader),
            1u);
  EXPECT_EQ(includedSlotsHeaders("techniques/x/a.cpp", "#include \"techniques/x/slots.h\"\n")
                .count("techniques/x/slots.h"),
            1u);
  // Two names bound at one number are caught; one name bound twice is not.
  const std::string twice = bad + "layout(binding = SB_SLOT_OTHER) uniform sampler2D c;\n" +
                            "layout(binding = SB_SLOT_VIEW) uniform sampler2D d;\n" +
                            "SB_UNIFORM_BLOCK(V, SB_SLOT_BLOCK)\n";
  EXPECT_EQ(boundNames(twice), (std::set<std::string>{"SB_SLOT_BLOCK", "SB_SLOT_NO_SUCH_THING",
                                                      "SB_SLOT_OTHER", "SB_SLOT_VIEW"}));
  EXPECT_EQ(collisions(boundNames(twice), {{"SB_SLOT_VIEW", 0}, {"SB_SLOT_OTHER", 0}}),
            (std::vector<std::string>{"SB_SLOT_OTHER and SB_SLOT_VIEW at 0"}));
  EXPECT_EQ(guardOf("techniques/dual_peel/slots.h"), "SB_DUAL_PEEL_SLOTS_H");
  EXPECT_EQ(guardOf("render/outputs/probe/slots.h"), "SB_PROBE_SLOTS_H");
}

TEST(Slots, NoShaderGivesABindingAsANumber) {
  auto files = shaderFiles();
  ASSERT_GT(files.size(), 40u);  // the scan sees the shaders
  // and the uniform blocks, which the shaders include
  for (const auto& f : cppFiles())
    if (f.ends_with("uniforms.h")) files.push_back(f);
  std::vector<std::string> found;
  for (const auto& f : files)
    for (const auto& hit : numericBindings(f, readText(kSource / f))) found.push_back(hit);
  for (const auto& hit : found)
    ADD_FAILURE() << hit << "\n  (name the slot in " << folderOf(hit)
                  << "/slots.h, or in render/common/slots.h if folders share it)";
}

TEST(Slots, EveryNameIsDefinedOnce) {
  const auto headers = slotHeaders();
  ASSERT_GT(headers.size(), 20u);  // the scan sees the folders' headers
  EXPECT_EQ(headers.front(), kCommonHeader);
  const Slots slots = allSlots();
  EXPECT_GT(slots.number.size(), 100u);
  for (const auto& t : slots.twice) ADD_FAILURE() << t << " both define it";
  for (const auto& h : headers)
    EXPECT_FALSE(slotDefines(readText(kSource / h)).empty()) << h << " defines no slot";
}

// A file names the shared slots and its own folder's only (a folder's names are
// its own), and a shader includes the header of every name it uses itself; a
// C++ file includes its folder's header itself (technique.h brings the common one).
TEST(Slots, EveryNameAFileUsesIsDefinedInCommonOrItsFolderAndIncluded) {
  const Slots slots = allSlots();
  std::size_t namingFiles = 0;
  auto check = [&](const std::string& f, bool shader) {
    const std::string text = readText(kSource / f);
    const auto used = slotNamesUsed(f, text);
    if (used.empty()) return;
    ++namingFiles;
    const std::string own = folderOf(f) + "/slots.h";
    const auto included = includedSlotsHeaders(f, text);
    for (const auto& [name, where] : used) {
      const auto it = slots.header.find(name);
      if (it == slots.header.end()) {
        ADD_FAILURE() << where << ": " << name << " is not defined in " << own << " or "
                      << kCommonHeader;
        continue;
      }
      EXPECT_TRUE(it->second == kCommonHeader || it->second == own)
          << where << ": " << name << " is " << it->second << "'s, not its folder's";
      if (shader || (it->second == own && own != kCommonHeader)) {
        EXPECT_TRUE(included.count(it->second))
            << where << ": " << name << " without #include of " << it->second;
      }
    }
  };
  for (const auto& f : shaderFiles()) check(f, true);
  EXPECT_GT(namingFiles, 25u);
  for (const auto& f : cppFiles()) check(f, false);
  EXPECT_GT(namingFiles, 45u);
}

// Readable as GLSL: comments, blank lines, the include guard and
// `#define SB_SLOT_NAME <number>` only (no #pragma once, no C++).
TEST(Slots, TheHeadersArePlainDefinesUnderAnIncludeGuard) {
  for (const auto& h : slotHeaders()) {
    const std::string guard = guardOf(h);
    const auto lines = splitLines(readText(kSource / h));
    const std::regex allowed(R"(^(//.*|\s*|#ifndef )" + guard + "|#define " + guard +
                             R"(|#endif(\s+//.*)?|#define SB_SLOT_[A-Z0-9_]+ [0-9]+(\s+//.*)?)$)");
    for (std::size_t i = 0; i < lines.size(); ++i)
      EXPECT_TRUE(std::regex_match(lines[i], allowed)) << h << ":" << i + 1 << ": " << lines[i];
    std::vector<std::string> directives;
    for (const auto& l : lines)
      if (l.rfind("#ifndef", 0) == 0 || l.rfind("#endif", 0) == 0) directives.push_back(l);
    EXPECT_EQ(directives, (std::vector<std::string>{"#ifndef " + guard, "#endif  // " + guard}))
        << h;
  }
}

// The C++ sees the same numbers as the shaders (the headers, parsed as text).
TEST(Slots, CppAndTheParsedHeadersAgree) {
  const auto& n = allSlots().number;
  EXPECT_EQ(n.at("SB_SLOT_VIEW"), int(sb::bind::kView));
  EXPECT_EQ(n.at("SB_SLOT_MESH_INDICES"), int(sb::bind::kMeshIndices));
  EXPECT_EQ(n.at("SB_SLOT_SHADOW_FIRST"), int(sb::bind::kShadowFirst));
  EXPECT_EQ(n.at("SB_SLOT_PROBE_VALUES"), SB_SLOT_PROBE_VALUES);
  EXPECT_EQ(n.at("SB_SLOT_OOIT_SLABS"), SB_SLOT_OOIT_SLABS);
  // weighted's C++ binds target i at SB_SLOT_BLENDED_TARGETS + i for both resolves.
  EXPECT_EQ(n.at("SB_SLOT_WEIGHTED_ACCUM"), SB_SLOT_BLENDED_TARGETS);
  EXPECT_EQ(n.at("SB_SLOT_WEIGHTED_COUNT"), SB_SLOT_BLENDED_TARGETS + 1);
  EXPECT_EQ(n.at("SB_SLOT_WBOIT_ACCUM"), SB_SLOT_BLENDED_TARGETS);
  EXPECT_EQ(n.at("SB_SLOT_WBOIT_REVEALAGE"), SB_SLOT_BLENDED_TARGETS + 1);
}

// A shadow technique's own slots lie in its range below the opaque shadow's
// (8..14) or in 0..7 (its compute and full-screen passes); every other folder's
// (transparency, outputs) lie outside 8..15, since their hair passes bind the
// shadow lookup beside their own.
TEST(Slots, EachFolderKeepsToItsRange) {
  std::set<std::string> shadowFolders;
  for (const auto* d : sb::techniques(sb::Family::Shadow))
    shadowFolders.insert("techniques/" + d->folder);
  const Slots slots = allSlots();
  const int first = slots.number.at("SB_SLOT_SHADOW_FIRST");
  const int opaque = slots.number.at("SB_SLOT_OPAQUE_SHADOW");
  ASSERT_EQ(slots.number.at("SB_SLOT_SHADOW_LAST"), opaque);
  for (const auto& [name, h] : slots.header) {
    if (h == kCommonHeader) continue;
    const int n = slots.number.at(name);
    if (shadowFolders.count(folderOf(h))) {
      EXPECT_LT(n, opaque) << h << ": " << name << " " << n;
    } else {
      EXPECT_TRUE(n < first || n > opaque) << h << ": " << name << " " << n;
    }
  }
}

// All bindings share descriptor set 0: in one shader, with everything it
// includes and each shadow technique's lookup in place of <shadow>, no two
// names share a number. A shader that includes <shadow> is a shading pass (over
// strands.vert or mesh.vert, which bind the shared 0..7) or probe's compute: it
// binds no name of its own folder in 0..7.
TEST(Slots, NoTwoNamesBoundInOneShaderShareANumber) {
  const Slots slots = allSlots();
  std::vector<std::string> lookups;
  for (const auto& f : shaderFiles())
    if (fs::path(f).filename() == "lookup.glsl") lookups.push_back(f);
  ASSERT_GE(lookups.size(), 13u);  // every shadow technique's, none's too
  // Every shading model's GLSL in place of <shading>, in turn with the lookups: with at least
  // as many lookups as models, each shader meets every model.
  std::vector<std::string> models;
  for (const auto& f : shaderFiles())
    if (fs::path(f).filename() == "shading.glsl" && f.rfind("render/common/", 0) != 0)
      models.push_back(f);
  ASSERT_GE(models.size(), 4u);
  ASSERT_GE(lookups.size(), models.size());
  std::size_t loaded = 0, withLookup = 0;
  for (const auto& f : shaderFiles()) {
    if (fs::path(f).extension() == ".glsl") continue;  // included by the others
    for (std::size_t i = 0; i < lookups.size(); ++i) {
      const std::string& lookup = lookups[i];
      sb::ShaderDefines defs;
      defs.aliases["shadow"] = lookup;
      defs.aliases["shading"] = models[i % models.size()];
      const sb::ShaderCode code = sb::loadShader(f, defs);
      ++loaded;
      const bool shading = std::count(code.fileNames.begin(), code.fileNames.end(), lookup) > 0;
      const auto names = boundNames(code.text);
      for (const auto& c : collisions(names, slots.number))
        ADD_FAILURE() << f << (shading ? " with " + lookup : "") << ": " << c;
      if (!shading) break;  // one load is enough: <shadow> is not included
      ++withLookup;
      for (const auto& name : names) {
        if (slots.number.count(name) &&
            slots.number.at(name) < slots.number.at("SB_SLOT_SHADOW_FIRST")) {
          EXPECT_EQ(slots.header.at(name), kCommonHeader)
              << f << ": " << name << " in 0..7, beside the shared geometry";
        }
      }
    }
  }
  EXPECT_GT(loaded, 60u);
  EXPECT_GT(withLookup, 100u);  // the shading passes, each with every lookup
}

// strands.vert includes slots.h twice (through bindings.glsl and view.glsl):
// the shader loader pastes it twice, the guard keeps one copy for glslang.
TEST(Slots, AShaderIncludingTheHeaderTwiceCompiles) {
  const sb::ShaderCode code = sb::loadShader("render/common/strands.vert");
  std::size_t pasted = 0;
  for (std::size_t at = 0; (at = code.text.find("#ifndef SB_SLOTS_H", at)) != std::string::npos;
       ++at)
    ++pasted;
  EXPECT_GE(pasted, 2u);
  EXPECT_FALSE(sb::compileVulkanSpirv(code, sb::ShaderStage::Vertex, "slots").empty());
}

}  // namespace
