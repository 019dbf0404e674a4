// One GLSL 4.50 source per shader for both APIs: this adds the #version line
// and the short per-API preamble, and maps compiler line numbers back to files.
#pragma once

#include <string>

#include "backends/device.h"

namespace sb {

enum class ShaderApi { GL, Vulkan };
enum class ShaderStage { Vertex, Fragment, Compute, Mesh };

// The complete text handed to the GL or glslang compiler.
std::string completeShaderSource(const ShaderCode& code, ShaderApi api);

// Rewrites "0:12:" / "ERROR: 0:12:" style locations in a compiler log into
// "file:line:" using code.fileNames, and prefixes shader and technique names.
std::string describeCompileError(const ShaderCode& code, const std::string& technique,
                                 const std::string& log);

}  // namespace sb
