// Bindings of the eye-space A-buffer (16 is the shared accumulation).
struct Fragment {
  vec4 color;  // shaded rgb, alpha
  uvec4 key;   // xy: fragment key
};
layout(std430, binding = 16) buffer Accum { vec4 accum[]; };
layout(std430, binding = 17) buffer Counts { uint counts[]; };
layout(std430, binding = 18) buffer Offsets { uint offsets[]; };
layout(std430, binding = 19) buffer Cursor { uint cursor[]; };
layout(std430, binding = 20) buffer Fragments { Fragment fragments[]; };
layout(std430, binding = 21) buffer Status { uint overflow; };
