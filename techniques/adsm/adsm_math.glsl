// Approximated deep shadows as TressFX ships them (AMD TressFX 1.0-3.x, first
// in Tomb Raider 2013; TressFXRendering.hlsl ComputeShadow): one depth map of
// the hair's front from the light; a point dz behind that front is taken to
// have dz / (fiber spacing x fiber radius) fibers in front of it, one more as
// soon as it is behind the front at all ("if occluded by hair, there is at
// least one fiber"), and visibility (1 - alpha)^fibers, averaged over a
// Gaussian PCF kernel of the depth map. Pure math, compiled as GLSL and,
// through adsm_math.h, as C++ with GLM for CPU tests.
#ifndef SB_INLINE
#define SB_INLINE
#endif

// Visibility of a point dzWorld (world units, >= 0) behind the hair's front,
// fiberDepth = spacing x radius (world units), shadow alpha alphaS.
SB_INLINE float adsmVisibility(float dzWorld, float fiberDepth, float alphaS) {
  if (!(dzWorld > 0.0f)) return 1.0f;
  float fibers = dzWorld / max(fiberDepth, 1e-12f) + 1.0f;
  return clamp(pow(1.0f - clamp(alphaS, 0.0f, 1.0f), fibers), 0.0f, 1.0f);
}

// TressFX's kernel weight for tap (dx, dy) of a kernel `size` taps wide:
// a Gaussian with sigma = (size / 2) / 2.4 (unnormalised: the lookup divides
// by the sum of the weights).
SB_INLINE float adsmKernelWeight(int dx, int dy, int size) {
  float sigma = max(float(size) * 0.5f / 2.4f, 1e-3f);
  return exp(-float(dx * dx + dy * dy) / (2.0f * sigma * sigma));
}
