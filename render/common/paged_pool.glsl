// Access by entry index to a pool split into pages of 2^SB_POOL_SHIFT entries,
// each its own storage array (a pool larger than one storage binding:
// fragment_lists.h, poolPageShift). Define first: SB_POOL_TYPE (an entry),
// SB_POOL_PAGES (1..5), SB_POOL_SHIFT, the arrays SB_POOL_PAGE0.. (those below
// SB_POOL_PAGES), the names SB_POOL_GET and, unless SB_POOL_READONLY,
// SB_POOL_SET. No include guard: a shader may hold two pools (the A-buffer's
// fill with exact's lookup); this file undefines them all at its end.
SB_POOL_TYPE SB_POOL_GET(uint i) {
#if SB_POOL_PAGES == 1
  return SB_POOL_PAGE0[i];
#else
  uint page = i >> SB_POOL_SHIFT, j = i & ((1u << SB_POOL_SHIFT) - 1u);
#if SB_POOL_PAGES > 4
  if (page == 4u) return SB_POOL_PAGE4[j];
#endif
#if SB_POOL_PAGES > 3
  if (page == 3u) return SB_POOL_PAGE3[j];
#endif
#if SB_POOL_PAGES > 2
  if (page == 2u) return SB_POOL_PAGE2[j];
#endif
  if (page == 1u) return SB_POOL_PAGE1[j];
  return SB_POOL_PAGE0[j];
#endif
}

#ifndef SB_POOL_READONLY
void SB_POOL_SET(uint i, SB_POOL_TYPE value) {
#if SB_POOL_PAGES == 1
  SB_POOL_PAGE0[i] = value;
#else
  uint page = i >> SB_POOL_SHIFT, j = i & ((1u << SB_POOL_SHIFT) - 1u);
#if SB_POOL_PAGES > 4
  if (page == 4u) SB_POOL_PAGE4[j] = value;
#endif
#if SB_POOL_PAGES > 3
  if (page == 3u) SB_POOL_PAGE3[j] = value;
#endif
#if SB_POOL_PAGES > 2
  if (page == 2u) SB_POOL_PAGE2[j] = value;
#endif
  if (page == 1u) SB_POOL_PAGE1[j] = value;
  if (page == 0u) SB_POOL_PAGE0[j] = value;
#endif
}
#endif

#undef SB_POOL_TYPE
#undef SB_POOL_PAGES
#undef SB_POOL_SHIFT
#undef SB_POOL_PAGE0
#undef SB_POOL_PAGE1
#undef SB_POOL_PAGE2
#undef SB_POOL_PAGE3
#undef SB_POOL_PAGE4
#undef SB_POOL_GET
#undef SB_POOL_SET
#undef SB_POOL_READONLY
