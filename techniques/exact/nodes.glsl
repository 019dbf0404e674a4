// exact's node pool: SB_EXACT_PAGES pages of 2^SB_EXACT_PAGE_SHIFT nodes, each
// within one storage binding (exact.cpp; one page unless the pool is larger
// than the device binds at once), read by node index through exactNode and,
// unless SB_EXACT_NODES_READONLY, written through setExactNode. The lookup and
// the passes of dsm and avsm are compiled before the pool is counted: with
// every page (the unused ones bound to 8 bytes).
#include "render/common/slots.h"
#ifndef SB_EXACT_PAGES
#define SB_EXACT_PAGES 1
#endif
#ifdef SB_EXACT_NODES_READONLY
#define SB_EXACT_NODES_ACCESS readonly
#else
#define SB_EXACT_NODES_ACCESS
#endif
layout(std430, binding = SB_SLOT_EXACT_NODES) SB_EXACT_NODES_ACCESS buffer ExactNodes {
  uvec2 exactNodes[];
};
#if SB_EXACT_PAGES > 1
layout(std430, binding = SB_SLOT_EXACT_PAGE1) SB_EXACT_NODES_ACCESS buffer ExactNodes1 {
  uvec2 exactNodes1[];
};
#endif
#if SB_EXACT_PAGES > 2
layout(std430, binding = SB_SLOT_EXACT_PAGE2) SB_EXACT_NODES_ACCESS buffer ExactNodes2 {
  uvec2 exactNodes2[];
};
#endif

// exactNode and setExactNode
#define SB_POOL_TYPE uvec2
#define SB_POOL_PAGES SB_EXACT_PAGES
#define SB_POOL_SHIFT SB_EXACT_PAGE_SHIFT
#define SB_POOL_PAGE0 exactNodes
#define SB_POOL_PAGE1 exactNodes1
#define SB_POOL_PAGE2 exactNodes2
#define SB_POOL_GET exactNode
#define SB_POOL_SET setExactNode
#ifdef SB_EXACT_NODES_READONLY
#define SB_POOL_READONLY
#endif
#include "render/common/paged_pool.glsl"
