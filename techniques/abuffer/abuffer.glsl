// Bindings of the eye-space A-buffer (16 is the shared accumulation).
#include "../common/slots.h"
struct Fragment {
  vec4 color;  // shaded rgb, alpha
  uvec4 key;   // xy: fragment key
};
layout(std430, binding = SB_SLOT_OIT_ACCUM) buffer Accum { vec4 accum[]; };
layout(std430, binding = SB_SLOT_OIT_COUNTS) buffer Counts { uint counts[]; };
layout(std430, binding = SB_SLOT_ABUFFER_OFFSETS) buffer Offsets { uint offsets[]; };
layout(std430, binding = SB_SLOT_ABUFFER_CURSOR) buffer Cursor { uint cursor[]; };
layout(std430, binding = SB_SLOT_ABUFFER_FRAGMENTS) buffer Fragments { Fragment fragments[]; };
layout(std430, binding = SB_SLOT_ABUFFER_STATUS) buffer Status {
  uint overflow;  // more fragments than counted
  uint dropped;   // fragments past a pixel's capacity (kbuffer: a full node pool)
  uint resolveCounter;
};
