// One step of depth peeling with exact tie-breaking, shared by the light
// (exact shadows) and the eye (exact transparency). A pixel's state is
// (previous key, current minimum key); `peeled` counts the layers taken so far.
// SB_PEEL_PASS 0: find the smallest depth after the previous key;
// SB_PEEL_PASS 1: among fragments at that depth, the smallest primitive id.
// Include after declaring `uvec4 peelState[]` and `uint peeled[]`.
bool afterPrevious(uint p, uvec2 key) {
  return peeled[p] == 0u || keyLess(peelState[p].xy, key);
}

void peelStep(uint p, uvec2 key) {
  if (!afterPrevious(p, key)) return;
#if SB_PEEL_PASS == 0
  atomicMin(peelState[p].z, key.x);
#else
  if (key.x == peelState[p].z) atomicMin(peelState[p].w, key.y);
#endif
}
