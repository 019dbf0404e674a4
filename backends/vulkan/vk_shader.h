// GLSL -> SPIR-V for the Vulkan backend (glslang C++ API), cached by source text.
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "backends/device.h"
#include "backends/shader_source.h"

namespace sb {

// Compiles code (completed with the Vulkan preamble) for one stage. Throws
// DeviceError with describeCompileError()'s message on a compile or link error.
// Results are cached per process by stage and complete source text.
// uniformsAsStorage: the uniform blocks (SB_UNIFORM_BLOCK) become read-only
// storage blocks of the same std140 layout, bound as storage buffers (see
// VulkanPlatform::uniformsAsStorage for why).
std::vector<uint32_t> compileVulkanSpirv(const ShaderCode& code, ShaderStage stage,
                                         const std::string& technique,
                                         bool uniformsAsStorage = false);

// The bindings of a module's StorageBuffer variables: a uniform block read as
// a storage buffer (uniformsAsStorage) needs a storage buffer descriptor, a
// block the shader declares `uniform` itself a uniform buffer one.
std::set<uint32_t> storageBufferBindings(const std::vector<uint32_t>& spirv);

}  // namespace sb
