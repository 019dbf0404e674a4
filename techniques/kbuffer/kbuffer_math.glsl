// The k-buffer of TressFX 4's per-pixel linked-list resolve (AMD TressFX 4.0,
// TressFXPPLL resolve, after Bavoil et al. 2007, "Multi-fragment effects on
// the GPU using the k-buffer"): the k nearest fragments of a pixel are kept in
// a small array; a fragment that does not fit (the farthest of the k+1) is
// blended at once into the tail, in arrival order, with "over"
// (C = a c + (1 - a) C, T = (1 - a) T); at the end the k kept fragments are
// blended back to front over the tail. Pure math, compiled as GLSL and,
// through kbuffer_math.h, as C++ with GLM for tests.
#ifndef SB_INLINE
#define SB_INLINE
#endif

#ifndef SB_KBUFFER_MAX
#define SB_KBUFFER_MAX 32  // the largest k; a shader sets it to its k
#endif

struct KBuffer {
  vec4 color[SB_KBUFFER_MAX];  // rgb, alpha
  uvec2 key[SB_KBUFFER_MAX];   // (depth bits, primitive id): fragment_key.glsl's order
  int size;
  vec4 tail;  // rgb: what was blended so far; a: its transmittance
};

SB_INLINE bool kbufferKeyLess(uvec2 a, uvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

SB_INLINE KBuffer kbufferEmpty() {
  KBuffer kb;
  for (int i = 0; i < SB_KBUFFER_MAX; ++i) {
    kb.color[i] = vec4(0.0f);
    kb.key[i] = uvec2(0u);
  }
  kb.size = 0;
  kb.tail = vec4(0.0f, 0.0f, 0.0f, 1.0f);
  return kb;
}

// "over": fragment f (rgb, alpha) in front of what `acc` holds.
SB_INLINE vec4 kbufferOver(vec4 acc, vec4 f) {
  return vec4(mix(vec3(acc.x, acc.y, acc.z), vec3(f.x, f.y, f.z), f.w), acc.w * (1.0f - f.w));
}

// Inserts fragment f with key `key` into a k-buffer of k (1..SB_KBUFFER_MAX)
// entries; the farthest of the k+1 goes to the tail.
SB_INLINE void kbufferInsert(SB_INOUT(KBuffer) kb, int k, vec4 f, uvec2 key) {
  if (kb.size < k) {
    kb.color[kb.size] = f;
    kb.key[kb.size] = key;
    kb.size += 1;
    return;
  }
  int far = 0;
  for (int i = 1; i < k; ++i)
    if (kbufferKeyLess(kb.key[far], kb.key[i])) far = i;
  if (kbufferKeyLess(key, kb.key[far])) {
    kb.tail = kbufferOver(kb.tail, kb.color[far]);
    kb.color[far] = f;
    kb.key[far] = key;
  } else {
    kb.tail = kbufferOver(kb.tail, f);
  }
}

// Blends the kept fragments back to front over the tail; returns the
// premultiplied front-to-back accumulation (rgb, 1 - T) that the exact
// techniques composite (common/composite.frag).
SB_INLINE vec4 kbufferResolve(KBuffer kb) {
  vec4 acc = kb.tail;
  for (int left = kb.size; left > 0; --left) {
    int far = 0;  // the farthest of the first `left` entries goes next
    for (int i = 1; i < left; ++i)
      if (kbufferKeyLess(kb.key[far], kb.key[i])) far = i;
    acc = kbufferOver(acc, kb.color[far]);
    kb.color[far] = kb.color[left - 1];
    kb.key[far] = kb.key[left - 1];
  }
  return vec4(acc.x, acc.y, acc.z, 1.0f - acc.w);
}
