// One vertex of a strand segment as the rasterizer gets it, written once for
// the vertex path (strands.vert: the segment's points pulled from the scene's
// buffers) and the mesh path (strands.mesh: the points made from the groom), so
// that both hand the rasterizer the same bits. A segment is 2 vertices as
// lines, or 6 as a camera-facing ribbon (SB_RIBBONS) whose width is set in
// pixels, so both APIs rasterize the same triangles. SB_WORLD: the ribbon is
// the strand's world width as projected at each end, at least one pixel, and
// its alpha is multiplied by the coverage, projected width / pixel clamped to
// 1 (analytic coverage, as production strand renderers draw hair).
// Needs view.glsl.
#ifdef SB_RIBBONS
#define SB_STRAND_CORNERS 6u
#else
#define SB_STRAND_CORNERS 2u
#endif

struct StrandVertex {
  vec4 clip;
  vec3 worldPos;
  vec3 tangent;
  vec4 color;
};

// Vertex `corner` (0..SB_STRAND_CORNERS-1) of the segment from p0 to p1 (xyz,
// thickness), whose ends have colours c0 and c1.
StrandVertex strandVertex(uint corner, vec4 p0, vec4 p1, vec4 c0, vec4 c1) {
  StrandVertex v;
#ifdef SB_RIBBONS
  const uint kEnd[6] = uint[6](0u, 1u, 1u, 0u, 1u, 0u);
  const float kSide[6] = float[6](-1.0, -1.0, 1.0, -1.0, 1.0, 1.0);
  uint end = kEnd[corner];
#else
  uint end = corner;
#endif
  vec3 p = end == 0u ? p0.xyz : p1.xyz;
  vec3 d = p1.xyz - p0.xyz;
  // A zero-length segment still needs a valid tangent for shading.
  v.tangent = dot(d, d) > 1e-30 ? normalize(d) : vec3(0.0, 1.0, 0.0);
  v.color = end == 0u ? c0 : c1;
  v.worldPos = p;
  vec4 clip = toViewClip(p);
#ifdef SB_RIBBONS
  vec4 e0 = toViewClip(p0.xyz);
  vec4 e1 = toViewClip(p1.xyz);
  vec2 s = (e1.xy / e1.w - e0.xy / e0.w) * viewViewport.xy;
  vec2 dir = dot(s, s) > 1e-12 ? normalize(s) : vec2(1.0, 0.0);
  vec2 normal = vec2(-dir.y, dir.x);
  float side = kSide[corner];
  float widthPx = viewViewport.z;
#ifdef SB_WORLD
  // The point's thickness (the view's fallback where the scene has none), in pixels: the
  // view-projection's y row has the projection's y scale as its length (the view is rigid),
  // and one pixel is 2 / height of NDC.
  float own = end == 0u ? p0.w : p1.w;
  float thickness = own > 0.0 ? own : viewViewport.w;
  float yScale = length(vec3(viewProj[0][1], viewProj[1][1], viewProj[2][1]));
  float projected = thickness * yScale / abs(clip.w) * 0.5 * viewViewport.y;
  widthPx = max(projected, 1.0);
  v.color.a *= min(projected, 1.0);
#endif
  // Half the width in pixels, converted to clip units at this vertex.
  clip.xy += normal * side * widthPx / viewViewport.xy * clip.w;
#endif
  v.clip = clip;
  return v;
}
