// A uniform block declared once for the C++ and the GLSL. A folder's blocks live
// in its uniforms.h (techniques/<folder>/uniforms.h; one header per block where
// different shaders bind them, e.g. osm/pass_uniforms.h, since a shader declares
// every block it includes; the shared ones in render/common/*_uniforms.h),
// which both languages include:
//
//   #include "render/common/uniform_block.h"
//   #include "techniques/<folder>/slots.h"
//   SB_UNIFORM_BLOCK(FooParams, <its slot>)
//     SB_FIELD(mat4, fooViewProj)
//     SB_FIELD(vec4, fooParams)  // bias, map size, shadow alpha, 0
//     SB_ARRAY(vec4, fooSlices, 129)
//   SB_UNIFORM_BLOCK_END(FooParams)
//
// The GLSL reads `layout(std140, binding = <its slot>) uniform FooParams
// { mat4 fooViewProj; vec4 fooParams; vec4 fooSlices[129]; };`, the C++ a struct
// sb::FooParams of the glm types with the same member names, whose layout is
// checked against std140 at compile time (render/common/std140.h). A type
// is a GLSL type name: float, int, uint, vec2..4, ivec2..4, uvec2..4, mat4.
// (techniques/osm/uniforms.h is one.)
//
// The shader loader (render/common/shader_library.cpp) resolves a quoted
// "techniques/..." include from the source root, as the C++ does, and skips the
// #includes under `#ifdef __cplusplus`, which are the C++'s.
#ifndef SB_UNIFORM_BLOCK_H
#define SB_UNIFORM_BLOCK_H

#ifdef __cplusplus
#include "render/common/std140.h"
#else
// clang-format off
#ifdef SB_UNIFORMS_AS_STORAGE
// The Vulkan backend on lavapipe (backends/vulkan/vk_platform.h says why): the
// same std140 block, read through a storage buffer.
#define SB_UNIFORM_BLOCK(Name, slot) layout(std140, binding = slot) readonly buffer Name {
#else
#define SB_UNIFORM_BLOCK(Name, slot) layout(std140, binding = slot) uniform Name {
#endif
#define SB_FIELD(type, name) type name;
#define SB_ARRAY(type, name, count) type name[count];
#define SB_UNIFORM_BLOCK_END(Name) };
// clang-format on
#endif

#endif  // SB_UNIFORM_BLOCK_H
