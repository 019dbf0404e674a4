// The opaque mesh, pulled from storage buffers (3 vertices per triangle).
#include "bindings.glsl"

layout(location = 0) out vec3 vWorldPos;
layout(location = 1) out vec3 vNormal;

void main() {
  uint index = meshIndices[uint(gl_VertexIndex)];
  vWorldPos = meshPositions[index].xyz;
  vNormal = meshNormals[index].xyz;
  gl_Position = toViewClip(vWorldPos);
}
