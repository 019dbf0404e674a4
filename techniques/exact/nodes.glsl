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
#if SB_EXACT_PAGES > 3
layout(std430, binding = SB_SLOT_EXACT_PAGE3) SB_EXACT_NODES_ACCESS buffer ExactNodes3 {
  uvec2 exactNodes3[];
};
#endif

#if SB_EXACT_PAGES == 1
uvec2 exactNode(uint i) { return exactNodes[i]; }
#ifndef SB_EXACT_NODES_READONLY
void setExactNode(uint i, uvec2 k) { exactNodes[i] = k; }
#endif
#else
uvec2 exactNode(uint i) {
  uint page = i >> SB_EXACT_PAGE_SHIFT, j = i & ((1u << SB_EXACT_PAGE_SHIFT) - 1u);
#if SB_EXACT_PAGES > 3
  if (page == 3u) return exactNodes3[j];
#endif
#if SB_EXACT_PAGES > 2
  if (page == 2u) return exactNodes2[j];
#endif
  if (page == 1u) return exactNodes1[j];
  return exactNodes[j];
}
#ifndef SB_EXACT_NODES_READONLY
void setExactNode(uint i, uvec2 k) {
  uint page = i >> SB_EXACT_PAGE_SHIFT, j = i & ((1u << SB_EXACT_PAGE_SHIFT) - 1u);
#if SB_EXACT_PAGES > 3
  if (page == 3u) exactNodes3[j] = k;
#endif
#if SB_EXACT_PAGES > 2
  if (page == 2u) exactNodes2[j] = k;
#endif
  if (page == 1u) exactNodes1[j] = k;
  if (page == 0u) exactNodes[j] = k;
}
#endif
#endif
