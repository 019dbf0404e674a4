// Filter kernels applied in a shadow lookup to the opacity (hair count) of the
// texels around a point before it becomes visibility, as Unreal's hair deep
// opacity maps do (HairStrandsDeepTransmittanceCommon.ush: SampleDOM_PCF2x2,
// SampleDOM_PCF). The includer defines SB_FILTER_OPACITY(texel), the opacity at
// the point's depth evaluated with texel `texel` (an ivec2 inside the map).
//   none    the point's texel
//   pcf2x2  bilinear between the 4 texels around the point
//   pcf6x4  Unreal's "PCF_6x4": a 3x3 grid of pcf2x2 samples 2 texels apart,
//           equal weights (a 6x6 footprint from 9 bilinear samples)
//   pcf6x6  every texel of the 6x6 footprint, equal weights
//   box3x3  the opacity shadow maps paper's own lookup (Kim & Neumann 2001,
//           section 3: "We use a 3x3 averaging kernel"): the point's texel
//           and its 8 neighbours, equal weights. Averaging each texel's
//           interpolated opacity is averaging the maps, then interpolating
//           (interpolation between two slices is linear).
const int kFilterNone = 0;
const int kFilterPcf2x2 = 1;
const int kFilterPcf6x4 = 2;
const int kFilterPcf6x6 = 3;
const int kFilterBox3x3 = 4;

#ifdef SB_FILTER_OPACITY

ivec2 filterClamp(ivec2 t, int size) { return clamp(t, ivec2(0), ivec2(size - 1)); }

// p: the point in texels (uv * size).
float filterPcf2x2(vec2 p, int size) {
  vec2 corner = floor(p - 0.5f);
  ivec2 c = ivec2(corner);
  vec2 s = p - 0.5f - corner;
  float h0 = SB_FILTER_OPACITY(filterClamp(c, size));
  float h1 = SB_FILTER_OPACITY(filterClamp(c + ivec2(1, 0), size));
  float h2 = SB_FILTER_OPACITY(filterClamp(c + ivec2(0, 1), size));
  float h3 = SB_FILTER_OPACITY(filterClamp(c + ivec2(1, 1), size));
  return mix(mix(h0, h1, s.x), mix(h2, h3, s.x), s.y);
}

float filteredOpacity(vec2 uv, int size, int kernel) {
  vec2 p = uv * float(size);
  if (kernel == kFilterPcf2x2) return filterPcf2x2(p, size);
  if (kernel == kFilterPcf6x4) {
    float sum = 0.0f;
    for (int y = -2; y <= 2; y += 2)
      for (int x = -2; x <= 2; x += 2) sum += filterPcf2x2(p + vec2(x, y), size);
    return sum / 9.0f;
  }
  if (kernel == kFilterPcf6x6) {
    // The 6x6 block around the point's own texel (3 before it, 2 after): it moves only when the
    // point crosses a texel edge. Placed from p - 0.5 it jumped at texel centres, where a light
    // ray through a texel centre sits, and visibility along that ray rose by float rounding.
    ivec2 c = ivec2(floor(p)) - ivec2(3);
    float sum = 0.0f;
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 6; ++x) sum += SB_FILTER_OPACITY(filterClamp(c + ivec2(x, y), size));
    return sum / 36.0f;
  }
  if (kernel == kFilterBox3x3) {
    ivec2 c = ivec2(floor(p));
    float sum = 0.0f;
    for (int y = -1; y <= 1; ++y)
      for (int x = -1; x <= 1; ++x) sum += SB_FILTER_OPACITY(filterClamp(c + ivec2(x, y), size));
    return sum / 9.0f;
  }
  return SB_FILTER_OPACITY(filterClamp(ivec2(p), size));
}
#endif
