// lowbias32 (Chris Wellons' hash prospector: good avalanche at two multiplies),
// the one 32-bit integer hash of the project, written once for C++ and GLSL
// (embedded with the shaders): the groom's generation rule (scenes/groom_rule.h)
// and stochastic transparency's coverage (techniques/stochastic/) draw the same
// bits on the CPU and on both APIs.
#ifndef SB_HASH_H
#define SB_HASH_H

#ifdef __cplusplus
#include <cstdint>
namespace sb {
inline uint32_t hash32(uint32_t x) {
#else
uint hash32(uint x) {
#endif
  x ^= x >> 16u;
  x *= 0x7feb352du;
  x ^= x >> 15u;
  x *= 0x846ca68bu;
  x ^= x >> 16u;
  return x;
}
#ifdef __cplusplus
}  // namespace sb
#endif

#endif  // SB_HASH_H
