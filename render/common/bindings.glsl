// Bindings shared by every geometry pass: the view and the scene's storage
// buffers, pulled by the vertex shaders. The numbers are named once in
// render/common/slots.h, which the C++ (technique.h, bind::) includes too.
#include "view.glsl"
#include "slots.h"
layout(std430, binding = SB_SLOT_POINTS) readonly buffer Points {
  vec4 points[];  // xyz, thickness
};
layout(std430, binding = SB_SLOT_COLORS) readonly buffer Colors {
  vec4 colors[];  // rgb, alpha
};
layout(std430, binding = SB_SLOT_SEGMENTS) readonly buffer Segments {
  uint segments[];  // a segment's first point
};
layout(std430, binding = SB_SLOT_MESH_POSITIONS) readonly buffer MeshPositions {
  vec4 meshPositions[];
};
layout(std430, binding = SB_SLOT_MESH_NORMALS) readonly buffer MeshNormals { vec4 meshNormals[]; };
layout(std430, binding = SB_SLOT_MESH_INDICES) readonly buffer MeshIndices { uint meshIndices[]; };
