// Bindings of the eye-space A-buffer (16 is the shared accumulation).
#include "render/common/slots.h"
struct Fragment {
  vec4 color;  // shaded rgb, alpha
  uvec4 key;   // xy: fragment key
};
layout(std430, binding = SB_SLOT_OIT_ACCUM) buffer Accum { vec4 accum[]; };
layout(std430, binding = SB_SLOT_OIT_COUNTS) buffer Counts { uint counts[]; };
layout(std430, binding = SB_SLOT_ABUFFER_OFFSETS) buffer Offsets { uint offsets[]; };
layout(std430, binding = SB_SLOT_ABUFFER_CURSOR) buffer Cursor { uint cursor[]; };
// The pool, in SB_ABUFFER_PAGES pages of 2^SB_ABUFFER_PAGE_SHIFT entries, each
// within one storage binding (abuffer.cpp; one page unless the pool is larger
// than the device binds at once): read and written by entry through
// fragmentAt and setFragment.
#ifndef SB_ABUFFER_PAGES
#define SB_ABUFFER_PAGES 1
#endif
layout(std430, binding = SB_SLOT_ABUFFER_FRAGMENTS) buffer Fragments { Fragment fragments[]; };
#if SB_ABUFFER_PAGES > 1
layout(std430, binding = SB_SLOT_ABUFFER_PAGE1) buffer Fragments1 { Fragment fragments1[]; };
#endif
#if SB_ABUFFER_PAGES > 2
layout(std430, binding = SB_SLOT_ABUFFER_PAGE2) buffer Fragments2 { Fragment fragments2[]; };
#endif
#if SB_ABUFFER_PAGES > 3
layout(std430, binding = SB_SLOT_ABUFFER_PAGE3) buffer Fragments3 { Fragment fragments3[]; };
#endif
#if SB_ABUFFER_PAGES > 4
layout(std430, binding = SB_SLOT_ABUFFER_PAGE4) buffer Fragments4 { Fragment fragments4[]; };
#endif
layout(std430, binding = SB_SLOT_ABUFFER_STATUS) buffer Status {
  uint overflow;  // more fragments than counted
  uint dropped;   // fragments past a pixel's capacity (kbuffer: a full node pool)
  uint resolveCounter;
};

// fragmentAt and setFragment
#define SB_POOL_TYPE Fragment
#define SB_POOL_PAGES SB_ABUFFER_PAGES
#define SB_POOL_SHIFT SB_ABUFFER_PAGE_SHIFT
#define SB_POOL_PAGE0 fragments
#define SB_POOL_PAGE1 fragments1
#define SB_POOL_PAGE2 fragments2
#define SB_POOL_PAGE3 fragments3
#define SB_POOL_PAGE4 fragments4
#define SB_POOL_GET fragmentAt
#define SB_POOL_SET setFragment
#include "render/common/paged_pool.glsl"
