// Dual scattering (Zinke, Yuksel, Weber & Keyser 2008, "Dual Scattering Approximation for Fast
// Multiple Scattering in Hair") on the Chiang fibre of chiang.glsl, as
// `--shading chiang:scattering=dual`. The light reaching a fragment through n strands is split as
// the paper splits it: the part that arrives directly (the shadow technique's visibility, which
// single scattering already used) and the part forward-scattered on the way, T_f = d_f a_f^n,
// spread in azimuth over the forward half circle and longitudinally by sigma_f^2 = n beta_f^2;
// both are back-scattered by the neighbouring strands (A_b, Delta_b, sigma_b, density d_b).
// n comes from the shadow technique's visibility: visibility = (1 - alpha_strand)^n.
// The fibre's averages over the hemispheres and the forward-spread lobes N^G_p are precomputed
// on the CPU from chiang's own table (dual_table.cpp) and appended to it:
//   [chiang's lobes 0..3][N^G_p, read as lobes 4..7 by chiangLobe][per (x, |sin theta|): the
//   fields below][chiang's opacity row]
// The density factors d_f, d_b are the model's uniforms (chiang's uniforms.h).
// Angles and variances are in u = theta_i + theta_o (d'Eon's lobe has variance v there), where
// the paper's shift and spread formulas, linear in the shifts and widths, hold unchanged.
// Compiled as GLSL (after chiang.glsl) and, through dual.h, as C++.
#ifndef SB_INLINE
#define SB_INLINE
#endif

#define SB_DUAL_LOBES (SB_CHIANG_LOBES * SB_CHIANG_X * SB_CHIANG_SIN * SB_CHIANG_PHI)
#define SB_DUAL_PARAMS (2 * SB_DUAL_LOBES)
// Per (x, |sin theta_i|): a_f, beta_f^2, A_b, sin and cos of Delta_b, sigma_b^2.
#define SB_DUAL_FIELDS 6
// chiang's opacity row (chiangOpacity), copied from its table.
#define SB_DUAL_OPACITY (SB_DUAL_PARAMS + SB_DUAL_FIELDS * SB_CHIANG_X * SB_CHIANG_SIN)
#define SB_DUAL_TABLE_SIZE (SB_DUAL_OPACITY + SB_CHIANG_X)
// The most strands counted between a point and the light (a_f^64 is below 1e-3 for every
// colour but white), and the widest lobe variance (a lobe this wide is nearly uniform).
#define SB_DUAL_MAX_N 64.0f
#define SB_DUAL_MAX_VARIANCE 8.0f

// Field k at (|sin theta_i|, x), bilinear.
SB_INLINE float dualField(int k, float sinI, float x, float xMax) {
  float fs = clamp(sinI, 0.0f, 1.0f) * float(SB_CHIANG_SIN - 1);
  float fx = clamp(x / xMax, 0.0f, 1.0f) * float(SB_CHIANG_X - 1);
  int is = min(int(fs), SB_CHIANG_SIN - 2);
  int ix = min(int(fx), SB_CHIANG_X - 2);
  float ts = fs - float(is);
  float tx = fx - float(ix);
  int b = SB_DUAL_PARAMS + (ix * SB_CHIANG_SIN + is) * SB_DUAL_FIELDS + k;
  int bx = b + SB_CHIANG_SIN * SB_DUAL_FIELDS;
  float lo = (1.0f - ts) * chiangTable[b] + ts * chiangTable[b + SB_DUAL_FIELDS];
  float hi = (1.0f - ts) * chiangTable[bx] + ts * chiangTable[bx + SB_DUAL_FIELDS];
  return (1.0f - tx) * lo + tx * hi;
}

// The strands between the point and the light from the shadow technique's visibility, each
// stopping strandAlpha of the light: visibility = (1 - alpha)^n. alpha is kept in
// [1e-3, 0.999] (a clear or an opaque strand still counts), visibility above 1e-4 (no
// shadow is complete), n at most SB_DUAL_MAX_N.
SB_INLINE float dualStrandCount(float visibility, float strandAlpha) {
  float a = clamp(strandAlpha, 1e-3f, 0.999f);
  float v = clamp(visibility, 1e-4f, 1.0f);
  return min(log(v) / log(1.0f - a), SB_DUAL_MAX_N);
}

// Dual scattering's light in two parts: what this fibre scatters itself (the direct light's
// single scattering and the forward-scattered light's, F_scatter's f_s^scatter), and what its
// neighbourhood scatters back (d_b f_back in F_direct and F_scatter). The back-scatter A_b is
// the light returned by every strand behind the point, so it belongs to the pixel, not to one
// of its layers: where the strands are see-through (chiang:opacity=fibre) the fibres behind are
// seen as well and their own light is already in A_b, so shading.glsl weights this part by
// the fragment's alpha (once over the layers), the fibre part by the fibre's coverage.
struct ChiangDualParts {
  vec3 fibre;
  vec3 neighbourhood;
};

// Arguments as chiang(), plus the density factors (d_f, d_b), the shadow technique's visibility
// and the strands' shadow alpha. Returns pi times the dual-scattering f cos per channel,
// visibility included (single scattering's direct light is visibility * chiang()), in its two
// parts.
SB_INLINE ChiangDualParts chiangDualParts(vec3 T, vec3 L, vec3 V, vec3 color, vec4 variance,
                                          vec4 tilt1, vec4 tilt4, vec2 density, float visibility,
                                          float strandAlpha) {
  const float pi = 3.14159265358979f;
  float vis = clamp(visibility, 0.0f, 1.0f);
  vec3 single = chiang(T, L, V, color, variance, tilt1, tilt4);
  float sinI = clamp(dot(L, T), -1.0f, 1.0f);
  float sinO = clamp(dot(V, T), -1.0f, 1.0f);
  float cosI = sqrt(max(0.0f, 1.0f - sinI * sinI));
  float cosO = sqrt(max(0.0f, 1.0f - sinO * sinO));
  float phi = hairAngles(T, L, V).z;
  vec3 x = -log(clamp(color, vec3(1e-3f), vec3(1.0f))) * tilt4.z;
  float df = density.x;
  float db = density.y;
  float n = dualStrandCount(vis, strandAlpha);
  // The paper's back-scatter spread in azimuth: uniform over the backward half circle.
  float sb = phi < 0.5f * pi ? 1.0f / pi : 0.0f;
  vec3 global3 = vec3(0.0f);
  vec3 back3 = vec3(0.0f);
  for (int c = 0; c < 3; ++c) {
    float xc = x[c];
    float af = max(dualField(0, abs(sinI), xc, tilt4.w), 1e-6f);
    float sf2 = n * dualField(1, abs(sinI), xc, tilt4.w);
    float ab = dualField(2, abs(sinI), xc, tilt4.w);
    float sd = dualField(3, abs(sinI), xc, tilt4.w);
    float cd = dualField(4, abs(sinI), xc, tilt4.w);
    float vb = dualField(5, abs(sinI), xc, tilt4.w);
    // theta_o rotated by -Delta_b: the back lobe peaks at theta_i + theta_o = Delta_b.
    float sinOb = sinO * cd - cosO * sd;
    float cosOb = abs(cosO * cd + sinO * sd);
    float backDirect = ab * sb * chiangMp(cosI, cosOb, sinI, sinOb, vb);
    float backScatter =
        ab * sb * chiangMp(cosI, cosOb, sinI, sinOb, min(vb + sf2, SB_DUAL_MAX_VARIANCE));
    // The forward-scattered light's last scattering: each lobe widened by sigma_f^2, its
    // azimuth spread over the forward half circle (N^G_p, lobes 4..7 of the table).
    float global = 0.0f;
    for (int p = 0; p < SB_CHIANG_LOBES; ++p) {
      float ss = p == 0 ? tilt1.z : (p == 1 ? -tilt1.x : (p == 2 ? -tilt4.x : 0.0f));
      float cs = p == 0 ? tilt1.w : (p == 1 ? tilt1.y : (p == 2 ? tilt4.y : 1.0f));
      float sinOp = sinO * cs + cosO * ss;
      float cosOp = abs(cosO * cs - sinO * ss);
      float v = min(variance[p] + sf2, SB_DUAL_MAX_VARIANCE);
      global += chiangMp(cosI, cosOp, sinI, sinOp, v) *
                chiangLobe(p + SB_CHIANG_LOBES, phi, abs(sinO), xc, tilt4.w);
    }
    // The paper's F_direct's back-scatter and F_scatter (its Fig. 5); T_f - directFraction
    // is kept >= 0 where the direct light is more than d_f a_f^n.
    float tf = df * exp(n * log(af));
    float scattered = max(tf - vis, 0.0f) * df;
    global3[c] = scattered * pi * global;
    back3[c] = vis * db * pi * backDirect + scattered * pi * db * pi * backScatter;
  }
  ChiangDualParts parts;
  parts.fibre = vis * single + global3;
  parts.neighbourhood = back3;
  return parts;
}

// Both parts together: the fragment's light where its alpha is the scene's.
SB_INLINE vec3 chiangDual(vec3 T, vec3 L, vec3 V, vec3 color, vec4 variance, vec4 tilt1,
                          vec4 tilt4, vec2 density, float visibility, float strandAlpha) {
  ChiangDualParts parts = chiangDualParts(T, L, V, color, variance, tilt1, tilt4, density,
                                          visibility, strandAlpha);
  return parts.fibre + parts.neighbourhood;
}
