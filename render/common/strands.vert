// Strands pulled from storage buffers by gl_VertexIndex: SB_STRAND_CORNERS
// vertices per segment (strand_vertex.glsl: lines or ribbons).
#include "bindings.glsl"
#include "strand_vertex.glsl"

layout(location = 0) out vec3 vWorldPos;
layout(location = 1) out vec3 vTangent;
layout(location = 2) out vec4 vColor;

void main() {
  uint seg = uint(gl_VertexIndex) / SB_STRAND_CORNERS;
  uint first = segments[seg];
  StrandVertex v = strandVertex(uint(gl_VertexIndex) % SB_STRAND_CORNERS, points[first],
                                points[first + 1u], colors[first], colors[first + 1u]);
  vWorldPos = v.worldPos;
  vTangent = v.tangent;
  vColor = v.color;
  gl_Position = v.clip;
}
