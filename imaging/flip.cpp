#include "imaging/flip.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <utility>

#include "base/errors.h"
#include "imaging/metrics.h"

namespace sb {
namespace flip {

namespace {

constexpr double kPi = 3.14159265358979323846;

// LDR-FLIP's constants (HPG 2020).
constexpr float kQc = 0.7f;    // exponent of the colour difference
constexpr float kPc = 0.4f;    // break point of the redistribution, a fraction of cmax
constexpr float kPt = 0.95f;   // ... mapped to this error
constexpr double kW = 0.082;   // width of the feature detectors, degrees
constexpr float kQf = 0.5f;    // exponent of the feature difference
constexpr float kT85 = 0.85f;  // HDR-FLIP: tone-mapped value that defines the exposures

// The contrast sensitivity functions in the spatial domain (HPG 2020, with
// its constants): S(x) = a1 sqrt(pi / b1) exp(-pi^2 x^2 / b1) + a2 sqrt(pi / b2)
// exp(-pi^2 x^2 / b2), x in degrees.
struct CsfConstants {
  double a1, b1, a2, b2;
};
constexpr CsfConstants kCsfA = {1.0, 0.0047, 0.0, 1e-5};
constexpr CsfConstants kCsfRG = {1.0, 0.0053, 0.0, 1e-5};
constexpr CsfConstants kCsfBY = {34.1, 0.04, 13.5, 0.025};

// Linear sRGB -> XYZ (IEC 61966-2-1 primaries, D65), in the exact rational form
// whose rows sum to the reference white used below.
constexpr float kRgbToXyz[3][3] = {
    {10135552.0f / 24577794.0f, 8788810.0f / 24577794.0f, 4435075.0f / 24577794.0f},
    {2613072.0f / 12288897.0f, 8788810.0f / 12288897.0f, 887015.0f / 12288897.0f},
    {1425312.0f / 73733382.0f, 8788810.0f / 73733382.0f, 70074185.0f / 73733382.0f},
};

struct Matrix3 {
  float m[3][3];
};

// The inverse of kRgbToXyz (cofactors / determinant, in double).
Matrix3 xyzToRgbMatrix() {
  double a[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a[i][j] = kRgbToXyz[i][j];
  const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                     a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                     a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  Matrix3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      // Cofactor of a[j][i] (transposed), cyclic indices.
      const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      r.m[i][j] = static_cast<float>((a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0]) / det);
    }
  return r;
}

const Matrix3& xyzToRgb() {
  static const Matrix3 m = xyzToRgbMatrix();
  return m;
}

// The reference white: XYZ of linear RGB (1, 1, 1).
constexpr std::array<float, 3> kWhite = {
    kRgbToXyz[0][0] + kRgbToXyz[0][1] + kRgbToXyz[0][2],
    kRgbToXyz[1][0] + kRgbToXyz[1][1] + kRgbToXyz[1][2],
    kRgbToXyz[2][0] + kRgbToXyz[2][1] + kRgbToXyz[2][2],
};

// ACES (Narkowicz's fit) applied to 0.6 x, as HDR-FLIP uses it:
// (a x^2 + b x + c) / (d x^2 + e x + f).
constexpr float kAces[6] = {0.6f * 0.6f * 2.51f, 0.6f * 0.03f, 0.0f,
                            0.6f * 0.6f * 2.43f, 0.6f * 0.59f, 0.14f};

float clamp01(float v) { return std::min(std::max(v, 0.0f), 1.0f); }

std::array<float, 3> mul(const float (&m)[3][3], const std::array<float, 3>& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
          m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

// The largest colour distance: green against blue (HPG 2020), ^ qc.
float maxColorDistance() {
  const auto huntLab = [](float r, float g, float b) {
    return huntAdjust(xyzToLab(linearRgbToXyz({r, g, b})));
  };
  return std::pow(hyab(huntLab(0, 1, 0), huntLab(0, 0, 1)), kQc);
}

// out = in convolved along rows with `taps` (centred, clamped at the border).
void filterRows(const std::vector<float>& in, std::vector<float>& out, int w, int h,
                const std::vector<float>& taps) {
  const int r = static_cast<int>(taps.size()) / 2;
  std::vector<float> padded(static_cast<std::size_t>(w + 2 * r));
  out.assign(static_cast<std::size_t>(w) * h, 0.0f);
  for (int y = 0; y < h; ++y) {
    const float* row = in.data() + static_cast<std::size_t>(y) * w;
    for (int x = -r; x < w + r; ++x)
      padded[static_cast<std::size_t>(x + r)] = row[std::clamp(x, 0, w - 1)];
    float* o = out.data() + static_cast<std::size_t>(y) * w;
    for (std::size_t k = 0; k < taps.size(); ++k) {
      const float t = taps[k];
      const float* p = padded.data() + k;
      for (int x = 0; x < w; ++x) o[x] += t * p[x];
    }
  }
}

// Row y of `in` convolved along columns with `taps` (centred, clamped at the
// border), into out[0, w). The second pass of a separable filter, a row at a
// time: the results are used at once and never stored whole.
void filterColumn(const std::vector<float>& in, int w, int h, int y, const std::vector<float>& taps,
                  float* out) {
  const int r = static_cast<int>(taps.size()) / 2;
  std::fill(out, out + w, 0.0f);
  for (int k = -r; k <= r; ++k) {
    const float t = taps[static_cast<std::size_t>(k + r)];
    const float* p = in.data() + static_cast<std::size_t>(std::clamp(y + k, 0, h - 1)) * w;
    for (int x = 0; x < w; ++x) out[x] += t * p[x];
  }
}

// One image's channels filtered along rows by the contrast sensitivity
// functions (blue-yellow twice: its two separable terms).
struct CsfRows {
  std::vector<float> a, rg, by1, by2;
};

CsfRows filterCsfRows(const Planes& ycxcz, const ContrastSensitivityFilters& f) {
  const int w = ycxcz.width, h = ycxcz.height;
  CsfRows o;
  filterRows(ycxcz.c[0], o.a, w, h, f.a);
  filterRows(ycxcz.c[1], o.rg, w, h, f.rg);
  filterRows(ycxcz.c[2], o.by1, w, h, f.by1);
  filterRows(ycxcz.c[2], o.by2, w, h, f.by2);
  return o;
}

// Row y of one image's YyCxCz filtered by the contrast sensitivity functions
// (the column pass), into yy, cx, cz (w each); `tmp` is w floats of scratch.
void filterCsfColumns(const CsfRows& rows, int w, int h, int y, const ContrastSensitivityFilters& f,
                      float* yy, float* cx, float* cz, float* tmp) {
  filterColumn(rows.a, w, h, y, f.a, yy);
  filterColumn(rows.rg, w, h, y, f.rg, cx);
  filterColumn(rows.by1, w, h, y, f.by1, cz);
  filterColumn(rows.by2, w, h, y, f.by2, tmp);
  for (int x = 0; x < w; ++x) cz[x] += tmp[x];
}

// One image's achromatic channel (Yy + 16) / 116 = Y / Yn, in [0, 1], filtered
// along rows by the Gaussian and its two derivatives.
struct FeatureRows {
  std::vector<float> g, dg, ddg;
};

FeatureRows filterFeatureRows(const Planes& ycxcz, const FeatureFilters& f) {
  const int w = ycxcz.width, h = ycxcz.height;
  std::vector<float> lum(ycxcz.size());
  for (std::size_t i = 0; i < lum.size(); ++i) lum[i] = (ycxcz.c[0][i] + 16.0f) / 116.0f;
  FeatureRows o;
  filterRows(lum, o.g, w, h, f.g);
  filterRows(lum, o.dg, w, h, f.dg);
  filterRows(lum, o.ddg, w, h, f.ddg);
  return o;
}

// Row y of the edge and point responses (the column pass): edge = |(d/dx, d/dy)|
// and point = |(d2/dx2, d2/dy2)| of the Gaussian-smoothed channel; `tmp` is 4 w floats.
void detectFeatures(const FeatureRows& rows, int w, int h, int y, const FeatureFilters& f,
                    float* edge, float* point, float* tmp) {
  float *dx = tmp, *ddx = tmp + w, *dy = tmp + 2 * w, *ddy = tmp + 3 * w;
  filterColumn(rows.dg, w, h, y, f.g, dx);
  filterColumn(rows.ddg, w, h, y, f.g, ddx);
  filterColumn(rows.g, w, h, y, f.dg, dy);
  filterColumn(rows.g, w, h, y, f.ddg, ddy);
  for (int x = 0; x < w; ++x) {
    edge[x] = std::sqrt(dx[x] * dx[x] + dy[x] * dy[x]);
    point[x] = std::sqrt(ddx[x] * ddx[x] + ddy[x] * ddy[x]);
  }
}

}  // namespace

Planes::Planes(int w, int h) : width(w), height(h) {
  for (auto& p : c) p.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0.0f);
}

float srgbToLinear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

std::array<float, 3> linearRgbToXyz(const std::array<float, 3>& rgb) { return mul(kRgbToXyz, rgb); }

std::array<float, 3> xyzToLinearRgb(const std::array<float, 3>& xyz) {
  return mul(xyzToRgb().m, xyz);
}

std::array<float, 3> xyzToYcxcz(const std::array<float, 3>& xyz) {
  const float x = xyz[0] / kWhite[0], y = xyz[1] / kWhite[1], z = xyz[2] / kWhite[2];
  return {116.0f * y - 16.0f, 500.0f * (x - y), 200.0f * (y - z)};
}

std::array<float, 3> ycxczToXyz(const std::array<float, 3>& ycxcz) {
  const float y = (ycxcz[0] + 16.0f) / 116.0f;
  const float x = y + ycxcz[1] / 500.0f, z = y - ycxcz[2] / 200.0f;
  return {x * kWhite[0], y * kWhite[1], z * kWhite[2]};
}

std::array<float, 3> xyzToLab(const std::array<float, 3>& xyz) {
  constexpr float kDelta = 6.0f / 29.0f;
  const auto f = [](float t) {
    return t > kDelta * kDelta * kDelta ? std::cbrt(t)
                                        : t / (3.0f * kDelta * kDelta) + 4.0f / 29.0f;
  };
  const float fx = f(xyz[0] / kWhite[0]), fy = f(xyz[1] / kWhite[1]), fz = f(xyz[2] / kWhite[2]);
  return {116.0f * fy - 16.0f, 500.0f * (fx - fy), 200.0f * (fy - fz)};
}

std::array<float, 3> huntAdjust(const std::array<float, 3>& lab) {
  return {lab[0], 0.01f * lab[0] * lab[1], 0.01f * lab[0] * lab[2]};
}

float hyab(const std::array<float, 3>& x, const std::array<float, 3>& y) {
  const float da = x[1] - y[1], db = x[2] - y[2];
  return std::fabs(x[0] - y[0]) + std::sqrt(da * da + db * db);
}

float redistributeColorError(float hyabDistance) {
  static const float cmax = maxColorDistance();
  const float pccmax = kPc * cmax;
  const float d = std::pow(hyabDistance, kQc);
  const float e =
      d < pccmax ? d * (kPt / pccmax) : kPt + (d - pccmax) / (cmax - pccmax) * (1.0f - kPt);
  return std::min(e, 1.0f);  // 1 is reached only by the green-blue distance
}

ContrastSensitivityFilters contrastSensitivityFilters(double ppd) {
  ContrastSensitivityFilters f;
  // Three standard deviations of the widest Gaussian, sqrt(b / (2 pi^2)) degrees.
  const double widest = std::max({kCsfA.b1, kCsfRG.b1, kCsfBY.b1, kCsfBY.b2});
  f.radius = static_cast<int>(std::ceil(3.0 * std::sqrt(widest / (2.0 * kPi * kPi)) * ppd));
  const auto gaussian = [](double a, double b, double x2) {
    return a * std::sqrt(kPi / b) * std::exp(-kPi * kPi * x2 / b);
  };
  const std::size_t n = static_cast<std::size_t>(2 * f.radius + 1);
  std::vector<double> a(n), rg(n), by1(n), by2(n);
  double sumA = 0, sumRG = 0, sumBY1 = 0, sumBY2 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = (static_cast<double>(i) - f.radius) / ppd;  // degrees
    const double x2 = x * x;
    a[i] = gaussian(kCsfA.a1, kCsfA.b1, x2);  // a2 = 0 for A and RG
    rg[i] = gaussian(kCsfRG.a1, kCsfRG.b1, x2);
    // S(r) = G1(x) G1(y) + G2(x) G2(y) with G = sqrt(a sqrt(pi / b)) exp(-pi^2 x^2 / b).
    by1[i] =
        std::sqrt(kCsfBY.a1 * std::sqrt(kPi / kCsfBY.b1)) * std::exp(-kPi * kPi * x2 / kCsfBY.b1);
    by2[i] =
        std::sqrt(kCsfBY.a2 * std::sqrt(kPi / kCsfBY.b2)) * std::exp(-kPi * kPi * x2 / kCsfBY.b2);
    sumA += a[i];
    sumRG += rg[i];
    sumBY1 += by1[i];
    sumBY2 += by2[i];
  }
  // Each two-dimensional filter sums to 1: for BY, sum1^2 + sum2^2.
  const double normBY = std::sqrt(sumBY1 * sumBY1 + sumBY2 * sumBY2);
  for (std::size_t i = 0; i < n; ++i) {
    f.a.push_back(static_cast<float>(a[i] / sumA));
    f.rg.push_back(static_cast<float>(rg[i] / sumRG));
    f.by1.push_back(static_cast<float>(by1[i] / normBY));
    f.by2.push_back(static_cast<float>(by2[i] / normBY));
  }
  return f;
}

FeatureFilters featureFilters(double ppd) {
  FeatureFilters f;
  const double sigma = 0.5 * kW * ppd;  // pixels
  f.radius = static_cast<int>(std::ceil(3.0 * sigma));
  const std::size_t n = static_cast<std::size_t>(2 * f.radius + 1);
  std::vector<double> g(n), dg(n), ddg(n);
  double sumG = 0, posD = 0, negD = 0, posDD = 0, negDD = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i) - f.radius;
    g[i] = std::exp(-x * x / (2.0 * sigma * sigma));
    dg[i] = -x * g[i];
    ddg[i] = (x * x / (sigma * sigma) - 1.0) * g[i];
    sumG += g[i];
    (dg[i] > 0 ? posD : negD) += std::fabs(dg[i]);
    (ddg[i] > 0 ? posDD : negDD) += std::fabs(ddg[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    f.g.push_back(static_cast<float>(g[i] / sumG));
    // At a very low ppd the Gaussian is one tap and a part of a derivative is
    // all zeros: those taps stay 0.
    const double dSum = dg[i] > 0 ? posD : negD, ddSum = ddg[i] > 0 ? posDD : negDD;
    f.dg.push_back(dSum > 0 ? static_cast<float>(dg[i] / dSum) : 0.0f);
    f.ddg.push_back(ddSum > 0 ? static_cast<float>(ddg[i] / ddSum) : 0.0f);
  }
  return f;
}

Planes linearRgbToYcxczPlanes(Planes rgb) {
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    const auto v = xyzToYcxcz(linearRgbToXyz({rgb.c[0][i], rgb.c[1][i], rgb.c[2][i]}));
    for (int c = 0; c < 3; ++c) rgb.c[c][i] = v[static_cast<std::size_t>(c)];
  }
  return rgb;
}

std::vector<float> colorDifference(const Planes& testYcxcz, const Planes& referenceYcxcz,
                                   const ContrastSensitivityFilters& f) {
  const int w = testYcxcz.width, h = testYcxcz.height;
  const CsfRows t = filterCsfRows(testYcxcz, f), r = filterCsfRows(referenceYcxcz, f);
  // Filtered YyCxCz -> linear RGB, clamped to [0, 1] -> CIELAB -> Hunt.
  const auto toHuntLab = [](float yy, float cx, float cz) {
    std::array<float, 3> rgb = xyzToLinearRgb(ycxczToXyz({yy, cx, cz}));
    for (float& v : rgb) v = clamp01(v);
    return huntAdjust(xyzToLab(linearRgbToXyz(rgb)));
  };
  std::vector<float> out(testYcxcz.size());
  std::vector<float> line(7 * static_cast<std::size_t>(w));
  float *ty = line.data(), *tcx = ty + w, *tcz = tcx + w, *ry = tcz + w, *rcx = ry + w,
        *rcz = rcx + w, *tmp = rcz + w;
  for (int y = 0; y < h; ++y) {
    filterCsfColumns(t, w, h, y, f, ty, tcx, tcz, tmp);
    filterCsfColumns(r, w, h, y, f, ry, rcx, rcz, tmp);
    float* o = out.data() + static_cast<std::size_t>(y) * w;
    for (int x = 0; x < w; ++x)
      o[x] = redistributeColorError(
          hyab(toHuntLab(ty[x], tcx[x], tcz[x]), toHuntLab(ry[x], rcx[x], rcz[x])));
  }
  return out;
}

std::vector<float> featureDifference(const Planes& testYcxcz, const Planes& referenceYcxcz,
                                     const FeatureFilters& f) {
  const int w = testYcxcz.width, h = testYcxcz.height;
  const FeatureRows t = filterFeatureRows(testYcxcz, f), r = filterFeatureRows(referenceYcxcz, f);
  const float norm = 1.0f / std::sqrt(2.0f);
  std::vector<float> out(testYcxcz.size());
  std::vector<float> line(8 * static_cast<std::size_t>(w));
  float *tEdge = line.data(), *tPoint = tEdge + w, *rEdge = tPoint + w, *rPoint = rEdge + w,
        *tmp = rPoint + w;
  for (int y = 0; y < h; ++y) {
    detectFeatures(t, w, h, y, f, tEdge, tPoint, tmp);
    detectFeatures(r, w, h, y, f, rEdge, rPoint, tmp);
    float* o = out.data() + static_cast<std::size_t>(y) * w;
    for (int x = 0; x < w; ++x) {
      const float d = std::max(std::fabs(tEdge[x] - rEdge[x]), std::fabs(tPoint[x] - rPoint[x]));
      o[x] = std::pow(std::min(norm * d, 1.0f), kQf);
    }
  }
  return out;
}

std::vector<float> combine(std::vector<float> colour, const std::vector<float>& feature) {
  for (std::size_t i = 0; i < colour.size(); ++i)
    colour[i] = std::pow(colour[i], 1.0f - feature[i]);
  return colour;
}

std::vector<float> ldrFlip(Planes testRgb, Planes referenceRgb, double ppd) {
  const Planes t = linearRgbToYcxczPlanes(std::move(testRgb));
  const Planes r = linearRgbToYcxczPlanes(std::move(referenceRgb));
  return combine(colorDifference(t, r, contrastSensitivityFilters(ppd)),
                 featureDifference(t, r, featureFilters(ppd)));
}

float toneMap(float v) {
  const float* k = kAces;
  return (v * v * k[0] + v * k[1] + k[2]) / (v * v * k[3] + v * k[4] + k[5]);
}

ExposureRange exposureRange(const Planes& referenceRgb) {
  // x85: the input the tone mapper takes to 0.85, the larger root of
  // (a - t d) x^2 + (b - t e) x + (c - t f) = 0.
  const double qa = kAces[0] - kT85 * kAces[3], qb = kAces[1] - kT85 * kAces[4],
               qc = kAces[2] - kT85 * kAces[5];
  const double half = -0.5 * qb / qa;
  const double x85 = half + std::sqrt(half * half - qc / qa);

  std::vector<float> lum(referenceRgb.size());
  for (std::size_t i = 0; i < lum.size(); ++i)
    lum[i] = linearRgbToXyz({referenceRgb.c[0][i], referenceRgb.c[1][i], referenceRgb.c[2][i]})[1];
  ExposureRange e;
  if (lum.empty()) return e;
  const float ymax = *std::max_element(lum.begin(), lum.end());
  if (!(ymax > 0.0f)) return e;  // black: start = stop = 0
  auto median = [](std::vector<float>& v) {
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
  };
  float ymedian = median(lum);
  if (!(ymedian > 0.0f)) {
    std::vector<float> lit;
    for (float y : lum)
      if (y > 0.0f) lit.push_back(y);
    ymedian = median(lit);
  }
  e.start = std::log2(x85 / ymax);
  e.stop = std::log2(x85 / ymedian);
  e.count = std::max(2, static_cast<int>(std::ceil(e.stop - e.start)));
  return e;
}

std::vector<float> hdrFlip(const Planes& testRgb, const Planes& referenceRgb, double ppd,
                           const ExposureRange& exposures) {
  std::vector<float> out(testRgb.size(), 0.0f);
  const double step = (exposures.stop - exposures.start) / (exposures.count - 1);
  for (int i = 0; i < exposures.count; ++i) {
    const float scale = static_cast<float>(std::exp2(exposures.start + i * step));
    const auto exposeAndToneMap = [scale](const Planes& p) {
      // The tone mapper passes 1 at 12.1 (and tends to 1.03): clamping its
      // input to +-1e6 changes nothing but keeps x^2 finite.
      Planes o(p.width, p.height);
      for (int c = 0; c < 3; ++c)
        for (std::size_t j = 0; j < p.size(); ++j)
          o.c[c][j] = clamp01(toneMap(std::clamp(p.c[c][j] * scale, -1e6f, 1e6f)));
      return o;
    };
    const std::vector<float> e =
        ldrFlip(exposeAndToneMap(testRgb), exposeAndToneMap(referenceRgb), ppd);
    for (std::size_t j = 0; j < out.size(); ++j) out[j] = std::max(out[j], e[j]);
  }
  return out;
}

}  // namespace flip

namespace {

using flip::Planes;

void checkFlipInputs(const Image& test, const Image& reference, double ppd) {
  if (!(ppd > 0.0 && ppd <= kFlipMaxPpd))
    throw std::invalid_argument("FLIP: pixels per degree must be in (0, " +
                                std::to_string(kFlipMaxPpd) + "], got " + std::to_string(ppd));
  for (const Image* img : {&test, &reference}) {
    const std::size_t expected = static_cast<std::size_t>(std::max(img->width, 0)) *
                                 static_cast<std::size_t>(std::max(img->height, 0)) *
                                 static_cast<std::size_t>(std::max(img->channels, 0));
    if (img->pixels.size() != expected)
      throw std::invalid_argument("FLIP: an image's pixel count does not match its size");
  }
  if (test.width != reference.width || test.height != reference.height)
    throw InputError("image sizes differ: " + std::to_string(test.width) + "x" +
                     std::to_string(test.height) + " vs " + std::to_string(reference.width) + "x" +
                     std::to_string(reference.height));
  if (test.channels < 3 || reference.channels < 3)
    throw InputError("FLIP compares RGB: images have " + std::to_string(test.channels) + " and " +
                     std::to_string(reference.channels) + " channels");
}

// RGB planes of an image, as linear RGB: LDR values clamped and sRGB-decoded. A
// NaN sample (HDR: any non-finite one) becomes 0 and marks its pixel in `bad`.
Planes linearPlanes(const Image& img, FlipInput input, std::vector<char>& bad) {
  Planes p(img.width, img.height);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      float v =
          img.pixels[i * static_cast<std::size_t>(img.channels) + static_cast<std::size_t>(c)];
      const bool invalid = input == FlipInput::Ldr ? std::isnan(v) : !std::isfinite(v);
      if (invalid) {
        bad[i] = 1;
        v = 0.0f;
      } else if (input == FlipInput::Ldr) {
        v = flip::srgbToLinear(std::clamp(v, 0.0f, 1.0f));
      }
      p.c[c][i] = v;
    }
  return p;
}

// flipWeightedPercentile of values sorted ascending.
double weightedPercentileOfSorted(const std::vector<float>& sorted, double p) {
  double total = 0.0;
  for (float v : sorted) total += v;
  double running = 0.0;
  for (float v : sorted) {
    running += v;
    if (running > p * total) return v;
  }
  return 0.0;
}

nlohmann::json number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

}  // namespace

FlipResult computeFlip(const Image& test, const Image& reference, const FlipOptions& options) {
  checkFlipInputs(test, reference, options.ppd);
  FlipResult r;
  r.width = test.width;
  r.height = test.height;
  r.ppd = options.ppd;
  r.input = options.input;
  if (test.empty()) return r;

  std::vector<char> bad(static_cast<std::size_t>(test.width) * test.height, 0);
  Planes t = linearPlanes(test, options.input, bad);
  Planes ref = linearPlanes(reference, options.input, bad);
  if (options.input == FlipInput::Hdr) {
    const flip::ExposureRange e = flip::exposureRange(ref);
    r.startExposure = e.start;
    r.stopExposure = e.stop;
    r.exposures = e.count;
    r.map = flip::hdrFlip(t, ref, options.ppd, e);
  } else {
    r.map = flip::ldrFlip(std::move(t), std::move(ref), options.ppd);
  }
  for (std::size_t i = 0; i < r.map.size(); ++i)
    if (bad[i]) {
      r.map[i] = 1.0f;
      ++r.nanPixels;
    }

  double sum = 0.0;
  r.min = 1.0;
  r.max = 0.0;
  for (float v : r.map) {
    sum += v;
    r.min = std::min(r.min, static_cast<double>(v));
    r.max = std::max(r.max, static_cast<double>(v));
  }
  r.mean = sum / static_cast<double>(r.map.size());
  std::vector<float> sorted = r.map;
  std::sort(sorted.begin(), sorted.end());
  r.weightedQ1 = weightedPercentileOfSorted(sorted, 0.25);
  r.weightedMedian = weightedPercentileOfSorted(sorted, 0.5);
  r.weightedQ3 = weightedPercentileOfSorted(sorted, 0.75);
  return r;
}

double flipWeightedPercentile(std::vector<float> values, double p) {
  std::sort(values.begin(), values.end());
  return weightedPercentileOfSorted(values, p);
}

nlohmann::json toJson(const FlipResult& r) {
  nlohmann::json j{{"mean", number(r.mean)},
                   {"weighted_median", number(r.weightedMedian)},
                   {"weighted_q1", number(r.weightedQ1)},
                   {"weighted_q3", number(r.weightedQ3)},
                   {"min", number(r.min)},
                   {"max", number(r.max)},
                   {"nan_pixels", r.nanPixels},
                   {"ppd", r.ppd},
                   {"input", r.input == FlipInput::Hdr ? "hdr" : "ldr"}};
  if (r.input == FlipInput::Hdr)
    j["exposures"] = {{"start", number(r.startExposure)},
                      {"stop", number(r.stopExposure)},
                      {"count", r.exposures}};
  return j;
}

std::array<float, 3> magma(double t) { return colourMap(ColourMap::Magma, t); }

Image flipErrorImage(const FlipResult& r) {
  Image out(r.width, r.height, 4, 1.0f);
  for (std::size_t i = 0; i < r.map.size(); ++i) {
    const auto rgb = magma(r.map[i]);
    for (int c = 0; c < 3; ++c)
      out.pixels[i * 4 + static_cast<std::size_t>(c)] = rgb[static_cast<std::size_t>(c)];
  }
  return out;
}

}  // namespace sb
