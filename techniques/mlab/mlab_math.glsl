// Multi-layer alpha blending (Salvi & Vaidyanathan 2014, "Multi-layer Alpha
// Blending", I3D): each pixel keeps L layers (premultiplied colour, the
// layer's transmittance, depth) sorted by depth. A fragment (c a, 1 - a) is
// inserted in depth order; when that makes L+1 layers the two farthest are
// merged, the farther under the nearer:
//   C = C_L + T_L C_{L+1},  T = T_L T_{L+1},  depth of the nearer.
// The result depends on the order fragments arrive in; the paper relies on
// ordered pixel synchronisation (the order primitives were submitted in).
// The resolve composites the layers front to back. Pure math, compiled as
// GLSL and, through mlab_math.h, as C++ with GLM for tests.
#ifndef SB_INLINE
#define SB_INLINE
#endif

#ifndef SB_MLAB_MAX
#define SB_MLAB_MAX 32  // the most layers; a shader sets it to its L
#endif

struct MlabLayers {
  vec4 layer[SB_MLAB_MAX + 1];  // rgb premultiplied, a: transmittance
  uvec2 key[SB_MLAB_MAX + 1];   // depth order (depth bits, primitive id)
  int size;
};

SB_INLINE MlabLayers mlabEmpty() {
  MlabLayers m;
  for (int i = 0; i <= SB_MLAB_MAX; ++i) {
    m.layer[i] = vec4(0.0f, 0.0f, 0.0f, 1.0f);
    m.key[i] = uvec2(0u);
  }
  m.size = 0;
  return m;
}

// Inserts fragment f (rgb, alpha) at depth key `key` into `layers` (1..SB_MLAB_MAX) layers.
SB_INLINE void mlabInsert(SB_INOUT(MlabLayers) m, int layers, vec4 f, uvec2 key) {
  vec4 frag = vec4(f.x * f.w, f.y * f.w, f.z * f.w, 1.0f - f.w);
  int j = m.size;
  while (j > 0 && (key.x < m.key[j - 1].x || (key.x == m.key[j - 1].x && key.y < m.key[j - 1].y))) {
    m.layer[j] = m.layer[j - 1];
    m.key[j] = m.key[j - 1];
    --j;
  }
  m.layer[j] = frag;
  m.key[j] = key;
  m.size += 1;
  if (m.size > layers) {  // merge the two farthest
    vec4 a = m.layer[layers - 1], b = m.layer[layers];
    m.layer[layers - 1] = vec4(a.x + a.w * b.x, a.y + a.w * b.y, a.z + a.w * b.z, a.w * b.w);
    m.size = layers;
  }
}

// Front to back: the premultiplied accumulation (rgb, 1 - T) that
// common/composite.frag puts over the opaque colour.
SB_INLINE vec4 mlabResolve(MlabLayers m) {
  vec3 c = vec3(0.0f);
  float t = 1.0f;
  for (int i = 0; i < m.size; ++i) {
    c += t * vec3(m.layer[i].x, m.layer[i].y, m.layer[i].z);
    t *= m.layer[i].w;
  }
  return vec4(c.x, c.y, c.z, 1.0f - t);
}
