#include "render/common/shader_library.h"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace sb {
namespace {

std::string readShaderFile(const std::string& path) {
  if (const char* dir = std::getenv("SB_SHADER_DIR")) {
    std::ifstream f(std::filesystem::path(dir) / path, std::ios::binary);
    if (!f) throw DeviceError("shader file not found: " + std::string(dir) + "/" + path);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
  }
  const auto& files = embeddedShaders();
  auto it = files.find(path);
  if (it == files.end()) throw DeviceError("shader file not embedded: " + path);
  return it->second;
}

void expand(const std::string& path, const ShaderDefines& defs, ShaderCode& out, int depth) {
  if (depth > 16) throw DeviceError("shader #include nesting too deep at " + path);
  const int fileIndex = static_cast<int>(out.fileNames.size());
  out.fileNames.push_back(path);
  std::istringstream in(readShaderFile(path));
  std::string line;
  int lineNo = 0;
  // Nesting depth of conditionals inside `#ifdef __cplusplus` (0: outside): a
  // header both languages read (render/common/uniform_block.h) keeps the C++'s
  // #includes there; they are left out (the GLSL preprocessor skips that part).
  int cppOnly = 0;
  out.text += "#line 1 " + std::to_string(fileIndex) + "\n";
  while (std::getline(in, line)) {
    ++lineNo;
    const auto start = line.find_first_not_of(" \t");
    const auto directive = [&](const char* d) {
      return start != std::string::npos && line.compare(start, std::strlen(d), d) == 0;
    };
    if (cppOnly > 0) {
      if (directive("#if")) ++cppOnly;
      if (directive("#endif") || (cppOnly == 1 && (directive("#else") || directive("#elif"))))
        --cppOnly;
      if (directive("#include")) {
        out.text += "\n";
        continue;
      }
    } else if (directive("#ifdef __cplusplus")) {
      cppOnly = 1;
    }
    if (start != std::string::npos && line.compare(start, 8, "#include") == 0) {
      const auto open = line.find_first_of("\"<", start + 8);
      const auto close = open == std::string::npos
                             ? std::string::npos
                             : line.find(line[open] == '"' ? '"' : '>', open + 1);
      if (close == std::string::npos)
        throw DeviceError(path + ":" + std::to_string(lineNo) + ": malformed #include");
      const std::string name = line.substr(open + 1, close - open - 1);
      std::string target;
      if (line[open] == '<') {
        auto a = defs.aliases.find(name);
        if (a == defs.aliases.end())
          throw DeviceError(path + ":" + std::to_string(lineNo) + ": no file bound to <" + name +
                            ">");
        target = a->second;
      } else if (name.rfind("techniques/", 0) == 0 || name.rfind("render/", 0) == 0 ||
                 name.rfind("base/", 0) == 0) {
        target = name;  // from the source root, as the C++ includes it
      } else {
        target = (std::filesystem::path(path).parent_path() / name).lexically_normal().string();
      }
      expand(target, defs, out, depth + 1);
      out.text += "#line " + std::to_string(lineNo + 1) + " " + std::to_string(fileIndex) + "\n";
      continue;
    }
    out.text += line + "\n";
  }
}

}  // namespace

ShaderCode loadShader(const std::string& path, const ShaderDefines& defs) {
  ShaderCode code;
  code.name = path;
  // Defines come first, attributed to the shader itself; #line resets numbering.
  for (const auto& [name, value] : defs.defines)
    code.text += "#define " + name + " " + value + "\n";
  expand(path, defs, code, 0);
  return code;
}

}  // namespace sb
