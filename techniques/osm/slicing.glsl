// Opacity shadow maps' slicing (Kim & Neumann 2001): where the slices lie and
// the opacity between them, over the shared opacity math (render/common/opacity.glsl).
// Pure math, compiled as GLSL and, through slicing.h, as C++ for CPU tests.
#ifndef SB_OSM_SLICING_GLSL
#define SB_OSM_SLICING_GLSL
#include "render/common/opacity.glsl"

// Slicing schemes of opacity shadow maps (paper Fig. 3); density is placed on
// the CPU from the hair's depth distribution (slicing.h).
const int kOsmUniform = 0;
const int kOsmDensity = 1;
const int kOsmGamma = 2;

// Depth D_i of OSM slice i in 0..n between the hair's near and far depth:
// uniform, or gamma (tighter near the light, where shadows vary most).
SB_INLINE float osmSliceDepth(int i, int n, float nearZ, float farZ, int mode, float gamma) {
  float f = float(i) / float(max(n, 1));
  if (mode == kOsmGamma) f = pow(f, gamma);
  return nearZ + (farZ - nearZ) * f;
}

#ifdef SB_LAYER_BOUND
// Opacity at depth z from n opacity maps. The includer defines (the layered maps'
// accessors: render/common/layered_glsl.h)
// SB_LAYER_BOUND(i): depth D_i (i = 0..n, increasing, D_0 = the hair's near
// depth) and SB_LAYER_MAP(i): map i (1..n), the opacity of the fragments in
// front of D_i; map 0 is 0. Linear interpolation between the two maps
// enclosing z; beyond D_n the last map.
SB_INLINE float osmOpacity(float z, int n) {
  if (n < 1 || !(z >= SB_LAYER_BOUND(0))) return 0.0f;
  if (z >= SB_LAYER_BOUND(n)) return SB_LAYER_MAP(n);
  int lo = 1;
  int hi = n;
  while (lo < hi) {  // smallest i with z < D_i
    int mid = (lo + hi) / 2;
    if (z < SB_LAYER_BOUND(mid))
      hi = mid;
    else
      lo = mid + 1;
  }
  float prev = lo > 1 ? SB_LAYER_MAP(lo - 1) : 0.0f;
  return opacityLerp(z, SB_LAYER_BOUND(lo - 1), SB_LAYER_BOUND(lo), prev, SB_LAYER_MAP(lo));
}
#endif
#endif  // SB_OSM_SLICING_GLSL
