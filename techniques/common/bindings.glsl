// Bindings shared by every geometry pass (numbers match techniques/common/technique.h).
layout(std140, binding = 0) uniform View {
  mat4 viewProj;
  vec4 viewEye;       // xyz position; w: 1 perspective, 0 orthographic
  vec4 viewForward;   // view direction (orthographic views)
  vec4 viewViewport;  // width, height, ribbon width in pixels, 0
};
layout(std430, binding = 2) readonly buffer Points { vec4 points[]; };    // xyz, thickness
layout(std430, binding = 3) readonly buffer Colors { vec4 colors[]; };    // rgb, alpha
layout(std430, binding = 4) readonly buffer Segments { uint segments[]; };  // first point
layout(std430, binding = 5) readonly buffer MeshPositions { vec4 meshPositions[]; };
layout(std430, binding = 6) readonly buffer MeshNormals { vec4 meshNormals[]; };
layout(std430, binding = 7) readonly buffer MeshIndices { uint meshIndices[]; };
