// Puts a pixel's list, entries [base .. base+n), in submission order (primitive
// id, then depth): the order ordered rasterization (fragment-shader interlock)
// processes fragments in. A list filled by atomic appends has no defined
// order; sorted this way a resolve that depends on order (mlab's merges,
// kbuffer's tail) gives the same image on every run and both APIs.
// Insertion sort: linear when the rasterizer appended in order already.
// Needs abuffer.glsl.
void sortBySubmission(uint base, uint n) {
  for (uint i = 1u; i < n; ++i) {
    Fragment f = fragmentAt(base + i);
    uint j = i;
    while (j > 0u && keyLess(f.key.yx, fragmentAt(base + j - 1u).key.yx)) {
      setFragment(base + j, fragmentAt(base + j - 1u));
      --j;
    }
    setFragment(base + j, f);
  }
}
