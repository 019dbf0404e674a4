// Binding numbers are named once, in techniques/common/slots.h, for the C++ and
// the GLSL: no shader under techniques/ spells a binding as a number, every
// SB_SLOT_ name a shader uses is defined there (and the shader includes the
// header itself), the header is plain #defines both languages read, and a
// shader that includes it twice still compiles (its include guard). The
// scanners are functions, shown to catch a bad line.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "backends/vulkan/vk_shader.h"
#include "techniques/common/shader_library.h"
#include "techniques/common/technique.h"

namespace {

namespace fs = std::filesystem;

const fs::path kSource = SB_SOURCE_DIR;
const fs::path kSlotsHeader = kSource / "techniques/common/slots.h";

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

// "file:line: text" for every binding given as a number (`binding = 3`, `binding=3`).
std::vector<std::string> numericBindings(const std::string& file, const std::string& text) {
  static const std::regex numeric(R"(\bbinding\s*=\s*[0-9])");
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

bool includesSlotsHeader(const std::string& text) {
  static const std::regex include(R"(^\s*#\s*include\s*"([^"]*/)?slots\.h")");
  for (const auto& l : splitLines(text))
    if (std::regex_search(l, include)) return true;
  return false;
}

// Every shader source under techniques/, as "techniques/..." paths.
std::vector<std::string> shaderFiles() {
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(kSource / "techniques")) {
    const std::string ext = e.path().extension().string();
    if (e.is_regular_file() &&
        (ext == ".glsl" || ext == ".vert" || ext == ".frag" || ext == ".comp"))
      files.push_back(fs::relative(e.path(), kSource).generic_string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(Slots, TheScannersCatchANumericBindingAndAnUnknownName) {
  const std::string bad =
      "// binding 3 in a comment is fine\n"
      "layout(std430, binding = 3) buffer X { uint x[]; };\n"
      "layout(binding = SB_SLOT_VIEW) uniform sampler2D a;\n"
      "layout(std140, binding=12) uniform Y { vec4 y; };\n"
      "layout(std430, binding = COUNTS_BINDING) buffer Z { uint z[]; };\n"
      "layout(binding = SB_SLOT_NO_SUCH_THING) uniform sampler2D b;\n";
  EXPECT_EQ(numericBindings("techniques/x/bad.frag", bad),
            (std::vector<std::string>{
                "techniques/x/bad.frag:2: layout(std430, binding = 3) buffer X { uint x[]; };",
                "techniques/x/bad.frag:4: layout(std140, binding=12) uniform Y { vec4 y; };"}));
  const auto used = slotNamesUsed("techniques/x/bad.frag", bad);
  EXPECT_EQ(used.size(), 2u);
  EXPECT_EQ(used.at("SB_SLOT_NO_SUCH_THING"), "techniques/x/bad.frag:6");
  const auto defs = slotDefines("#define SB_SLOT_VIEW 0\n#define SB_SLOTS_H\n");
  EXPECT_EQ(defs, (std::map<std::string, int>{{"SB_SLOT_VIEW", 0}}));
  EXPECT_FALSE(defs.count("SB_SLOT_NO_SUCH_THING"));
  EXPECT_FALSE(includesSlotsHeader(bad));
  EXPECT_TRUE(includesSlotsHeader("#include \"../common/slots.h\"\n"));
}

TEST(Slots, NoShaderGivesABindingAsANumber) {
  const auto files = shaderFiles();
  ASSERT_GT(files.size(), 40u);  // the scan sees the shaders
  std::vector<std::string> found;
  for (const auto& f : files)
    for (const auto& hit : numericBindings(f, readText(kSource / f))) found.push_back(hit);
  for (const auto& hit : found)
    ADD_FAILURE() << hit << "\n  (name the slot in techniques/common/slots.h)";
}

TEST(Slots, EveryNameAShaderUsesIsDefinedAndIncluded) {
  const auto defs = slotDefines(readText(kSlotsHeader));
  ASSERT_GT(defs.size(), 50u);
  std::size_t namingFiles = 0;
  for (const auto& f : shaderFiles()) {
    const std::string text = readText(kSource / f);
    const auto used = slotNamesUsed(f, text);
    for (const auto& [name, where] : used)
      EXPECT_TRUE(defs.count(name)) << where << ": " << name << " is not defined in slots.h";
    if (used.empty()) continue;
    ++namingFiles;
    EXPECT_TRUE(includesSlotsHeader(text)) << f << " names slots without #include \"slots.h\"";
  }
  EXPECT_GT(namingFiles, 25u);
}

// Readable as GLSL: comments, blank lines, the include guard and
// `#define SB_SLOT_NAME <number>` only (no #pragma once, no C++).
TEST(Slots, TheHeaderIsPlainDefinesUnderAnIncludeGuard) {
  const auto lines = splitLines(readText(kSlotsHeader));
  static const std::regex allowed(
      R"(^(//.*|\s*|#ifndef SB_SLOTS_H|#define SB_SLOTS_H|#endif(\s+//.*)?|)"
      R"(#define SB_SLOT_[A-Z0-9_]+ [0-9]+(\s+//.*)?)$)");
  for (std::size_t i = 0; i < lines.size(); ++i)
    EXPECT_TRUE(std::regex_match(lines[i], allowed))
        << "techniques/common/slots.h:" << i + 1 << ": " << lines[i];
  std::vector<std::string> directives;
  for (const auto& l : lines)
    if (l.rfind("#ifndef", 0) == 0 || l.rfind("#endif", 0) == 0) directives.push_back(l);
  EXPECT_EQ(directives, (std::vector<std::string>{"#ifndef SB_SLOTS_H", "#endif  // SB_SLOTS_H"}));
}

// The C++ sees the same numbers as the shaders (the header, parsed as text).
TEST(Slots, CppAndTheParsedHeaderAgree) {
  const auto defs = slotDefines(readText(kSlotsHeader));
  EXPECT_EQ(defs.at("SB_SLOT_VIEW"), int(sb::bind::kView));
  EXPECT_EQ(defs.at("SB_SLOT_MESH_INDICES"), int(sb::bind::kMeshIndices));
  EXPECT_EQ(defs.at("SB_SLOT_SHADOW_FIRST"), int(sb::bind::kShadowFirst));
  EXPECT_EQ(defs.at("SB_SLOT_PROBE_VALUES"), SB_SLOT_PROBE_VALUES);
  EXPECT_EQ(defs.at("SB_SLOT_OOIT_SLABS"), SB_SLOT_OOIT_SLABS);
}

// strands.vert includes slots.h twice (through bindings.glsl and view.glsl):
// the shader loader pastes it twice, the guard keeps one copy for glslang.
TEST(Slots, AShaderIncludingTheHeaderTwiceCompiles) {
  const sb::ShaderCode code = sb::loadShader("techniques/common/strands.vert");
  std::size_t pasted = 0;
  for (std::size_t at = 0; (at = code.text.find("#ifndef SB_SLOTS_H", at)) != std::string::npos;
       ++at)
    ++pasted;
  EXPECT_GE(pasted, 2u);
  EXPECT_FALSE(sb::compileVulkanSpirv(code, sb::ShaderStage::Vertex, "slots").empty());
}

}  // namespace
