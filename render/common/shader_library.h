// Loads a technique's GLSL (embedded in the binary at build time) and resolves
// #include "file" (relative to the including file; "techniques/..." and
// "render/..." from the source root), #include <alias> (#includes under `#ifdef __cplusplus` are
// left out: the C++'s, in a header both languages read), keeping #line numbers so compile errors
// name the right file and line.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "backends/device.h"

namespace sb {

struct ShaderDefines {
  std::vector<std::pair<std::string, std::string>> defines;  // #define NAME VALUE
  std::map<std::string, std::string> aliases;                // <alias> -> file path
  // Adds another set's defines and aliases (e.g. the hair shading's).
  ShaderDefines& add(const ShaderDefines& more) {
    defines.insert(defines.end(), more.defines.begin(), more.defines.end());
    for (const auto& [alias, file] : more.aliases) aliases[alias] = file;
    return *this;
  }
};

// path is relative to the source tree, e.g. "techniques/shadowmap/depth.frag".
// When SB_SHADER_DIR is set in the environment, files are read from that
// folder instead of the embedded copies (for editing shaders without a rebuild).
ShaderCode loadShader(const std::string& path, const ShaderDefines& defs = {});

// Generated: every shader file, and every unit folder's unit.json (the registry reads it).
const std::map<std::string, std::string>& embeddedShaders();

}  // namespace sb
