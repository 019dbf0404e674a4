// Puts a pixel's list fragments[base .. base+n) in submission order (primitive
// id, then depth): the order ordered rasterization (fragment-shader interlock)
// processes fragments in. A list filled by atomic appends has no defined
// order; sorted this way a resolve that depends on order (mlab's merges,
// kbuffer's tail) gives the same image on every run and both APIs.
// Insertion sort: linear when the rasterizer appended in order already.
// Needs abuffer.glsl.
void sortBySubmission(uint base, uint n) {
  for (uint i = 1u; i < n; ++i) {
    Fragment f = fragments[base + i];
    uint j = i;
    while (j > 0u && keyLess(f.key.yx, fragments[base + j - 1u].key.yx)) {
      fragments[base + j] = fragments[base + j - 1u];
      --j;
    }
    fragments[base + j] = f;
  }
}
