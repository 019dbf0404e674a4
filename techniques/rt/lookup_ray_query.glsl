// Ray-traced strand shadows, ray-query tier (VK_KHR_ray_query): the segments
// a ray may cross are the candidates of a ray query over an acceleration
// structure of their boxes (Device::createAccelerationStructure; a box's
// index is its segment's in rtSegments), each judged by the same rule as the
// software tier (rtCrosses, rays.glsl). No candidate is confirmed: the query
// goes on through every box on the ray, and a ray stops only at max_hits.
#extension GL_EXT_ray_query : require
#include "rays.glsl"
#include "slots.h"

layout(binding = SB_SLOT_RT_SCENE) uniform accelerationStructureEXT rtScene;

float rtTransmittance(vec3 o, vec3 d, float tMax, float zLimit) {
  float T = 1.0;
  uint hits = 0u;
  rayQueryEXT q;
  rayQueryInitializeEXT(q, rtScene, gl_RayFlagsNoOpaqueEXT, 0xFF, o, 0.0, d, tMax);
  while (rayQueryProceedEXT(q)) {
    if (rayQueryGetIntersectionTypeEXT(q, false) != gl_RayQueryCandidateIntersectionAABBEXT)
      continue;
    uint i = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false));
    if (rtCrosses(i, o, d, tMax, zLimit) && rtCross(T, hits)) {
      rayQueryTerminateEXT(q);
      break;
    }
  }
  return T;
}
