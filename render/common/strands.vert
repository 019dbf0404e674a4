// Strands pulled from storage buffers by gl_VertexIndex: 2 vertices per segment
// as lines, or 6 per segment as a camera-facing ribbon (SB_RIBBONS) whose width
// is set in pixels, so both APIs rasterize the same triangles. SB_WORLD: the
// ribbon is the strand's world width as projected at each end, at least one
// pixel, and its alpha is multiplied by the coverage, projected width / pixel
// clamped to 1 (analytic coverage, as production strand renderers draw hair).
#include "bindings.glsl"

layout(location = 0) out vec3 vWorldPos;
layout(location = 1) out vec3 vTangent;
layout(location = 2) out vec4 vColor;

void main() {
#ifdef SB_RIBBONS
  const uint kEnd[6] = uint[6](0u, 1u, 1u, 0u, 1u, 0u);
  const float kSide[6] = float[6](-1.0, -1.0, 1.0, -1.0, 1.0, 1.0);
  uint seg = uint(gl_VertexIndex) / 6u;
  uint end = kEnd[uint(gl_VertexIndex) % 6u];
#else
  uint seg = uint(gl_VertexIndex) >> 1u;
  uint end = uint(gl_VertexIndex) & 1u;
#endif
  uint first = segments[seg];
  vec3 p0 = points[first].xyz;
  vec3 p1 = points[first + 1u].xyz;
  vec3 p = end == 0u ? p0 : p1;
  vec3 d = p1 - p0;
  // A zero-length segment still needs a valid tangent for shading.
  vTangent = dot(d, d) > 1e-30 ? normalize(d) : vec3(0.0, 1.0, 0.0);
  vColor = colors[first + end];
  vWorldPos = p;
  vec4 clip = toViewClip(p);
#ifdef SB_RIBBONS
  vec4 c0 = toViewClip(p0);
  vec4 c1 = toViewClip(p1);
  vec2 s = (c1.xy / c1.w - c0.xy / c0.w) * viewViewport.xy;
  vec2 dir = dot(s, s) > 1e-12 ? normalize(s) : vec2(1.0, 0.0);
  vec2 normal = vec2(-dir.y, dir.x);
  float side = kSide[uint(gl_VertexIndex) % 6u];
  float widthPx = viewViewport.z;
#ifdef SB_WORLD
  // The point's thickness (the view's fallback where the scene has none), in pixels: the
  // view-projection's y row has the projection's y scale as its length (the view is rigid),
  // and one pixel is 2 / height of NDC.
  float thickness = points[first + end].w > 0.0 ? points[first + end].w : viewViewport.w;
  float yScale = length(vec3(viewProj[0][1], viewProj[1][1], viewProj[2][1]));
  float projected = thickness * yScale / abs(clip.w) * 0.5 * viewViewport.y;
  widthPx = max(projected, 1.0);
  vColor.a *= min(projected, 1.0);
#endif
  // Half the width in pixels, converted to clip units at this vertex.
  clip.xy += normal * side * widthPx / viewViewport.xy * clip.w;
#endif
  gl_Position = clip;
}
