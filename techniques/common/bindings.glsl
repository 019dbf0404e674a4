// Bindings shared by every geometry pass (numbers match techniques/common/technique.h):
// the view and the scene's storage buffers, pulled by the vertex shaders.
#include "view.glsl"
layout(std430, binding = 2) readonly buffer Points { vec4 points[]; };    // xyz, thickness
layout(std430, binding = 3) readonly buffer Colors { vec4 colors[]; };    // rgb, alpha
layout(std430, binding = 4) readonly buffer Segments { uint segments[]; };  // first point
layout(std430, binding = 5) readonly buffer MeshPositions { vec4 meshPositions[]; };
layout(std430, binding = 6) readonly buffer MeshNormals { vec4 meshNormals[]; };
layout(std430, binding = 7) readonly buffer MeshIndices { uint meshIndices[]; };
