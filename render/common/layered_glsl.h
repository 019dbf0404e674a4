// The C++ side of GLSL math over layered opacity maps (DOM's layers, OSM's slices): the
// GLSL reads a map's boundary k (0..n, increasing) through SB_LAYER_BOUND(k) and its layer k
// (1..n) through SB_LAYER_MAP(k); here they read layerBoundsCpu[k] and layerMapsCpu[k - 1],
// which the caller sets. A folder's header compiles its GLSL file as C++ in sb::glsl with
//   #define SB_LAYERED_GLSL "techniques/<folder>/<file>.glsl"
//   #include "render/common/layered_glsl.h"
// (no #pragma once: included once per file; the GLSL file keeps its own guard).
#ifndef SB_LAYERED_GLSL_ACCESSORS
#define SB_LAYERED_GLSL_ACCESSORS
namespace sb::glsl {
inline const float* layerBoundsCpu = nullptr;  // boundary 0..n
inline const float* layerMapsCpu = nullptr;    // layer 1..n at [0..n-1]
}  // namespace sb::glsl
#endif

namespace sb::glsl {
#define SB_INLINE inline
#define SB_LAYER_BOUND(k) layerBoundsCpu[k]
#define SB_LAYER_MAP(k) layerMapsCpu[(k)-1]
#include SB_LAYERED_GLSL
#undef SB_LAYER_MAP
#undef SB_LAYER_BOUND
#undef SB_INLINE
}  // namespace sb::glsl
#undef SB_LAYERED_GLSL
