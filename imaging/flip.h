// FLIP, a perceptual difference between a test image and a reference image:
// LDR-FLIP (Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom and
// Fairchild, "FLIP: A Difference Evaluator for Alternating Images", HPG 2020)
// and HDR-FLIP (Andersson, Nilsson, Shirley and Akenine-Moller, "Visualizing
// Errors in Rendered High Dynamic Range Images", Eurographics 2021 short paper).
//
// Per pixel, FLIP is in [0, 1]: 0 where an observer at `ppd` pixels per degree
// sees no difference, 1 for the largest (green against blue). The stages, one
// function each below (namespace sb::flip), as the papers name them:
//  colour pipeline: linear RGB -> YyCxCz (opponent space, linear in XYZ) ->
//    spatial filtering by the contrast sensitivity functions of the three
//    channels at `ppd` -> back to linear RGB, clamped to [0, 1] -> CIELAB ->
//    Hunt adjustment -> HyAB distance -> redistribution to [0, 1]
//    (exponent qc = 0.7, break point pc = 0.4 of cmax, the green-blue distance,
//    mapped to pt = 0.95);
//  feature pipeline: edge (first derivative) and point (second derivative)
//    detectors, Gaussian derivatives with sigma = 0.5 * 0.082 degrees, on the
//    achromatic channel; difference max(|edges|, |points|) / sqrt(2) raised to
//    qf = 0.5;
//  combination: colour difference ^ (1 - feature difference).
//  HDR-FLIP: exposures from the reference's luminance (start log2(x85 / Ymax),
//    stop log2(x85 / Ymedian), x85 the input that the tone mapper takes to 0.85;
//    max(2, ceil(stop - start)) exposures evenly spaced), each image scaled by
//    2^exposure, tone mapped (ACES, Narkowicz's fit with the 0.6 pre-exposure),
//    clamped, compared by LDR-FLIP; per pixel the largest error over exposures.
// Filters are separable (the blue-yellow filter, a sum of two Gaussians, as two
// separable terms) and clamp at the image border.
//
// Agreement: NVIDIA's reference implementation (github.com/NVlabs/flip, v1.6,
// its C++ tool) prints the same mean FLIP to within 2.2e-5 on nine rendered
// 512x512 pairs, PNG and EXR, at 67 ppd (the tool sums in float; its error
// maps averaged in double agree to 1e-7). tests/test_flip.cpp holds a 64x64
// pair and the tool's numbers. One deliberate difference: where half the
// reference's pixels are black (a dark background), the tool's stop exposure
// log2(x85 / 0) is infinite and its HDR-FLIP breaks down (mean 0); here the
// median of the non-zero luminances is used (flip::exposureRange).
//
// Input: an LDR image holds display values, sRGB-encoded, in [0, 1]: what a PNG
// holds and what a viewer shows (strandbench writes its raw colour values to
// PNGs, so that is how its images are seen); they are clamped to [0, 1] as a
// display would, then decoded to linear RGB. An HDR image (EXR) holds linear
// RGB of any range. Only RGB (channels 0..2) is compared.
//
// NaN policy (as imaging/metrics.h: a NaN must never make two images look
// alike): a pixel with a NaN sample in either image (for HDR input, also an
// infinite one) is a "NaN pixel": its FLIP is 1, the largest error, it is
// counted in nanPixels, and its samples count as 0 for the filters of its
// neighbours and for the exposure range. An LDR input's infinities are clamped
// to [0, 1] like any other value.
#pragma once

#include <array>
#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <vector>

#include "imaging/image.h"

namespace sb {

// The papers' viewing condition: 0.7 m from a 0.7 m wide 3840-pixel display
// gives 67 pixels per degree.
constexpr double kFlipDefaultPpd = 67.0;
// The largest ppd accepted (filters 2 * 3 sigma wide: 273 taps at 1000).
constexpr double kFlipMaxPpd = 1000.0;

enum class FlipInput {
  Ldr,  // display (sRGB-encoded) values in [0, 1]: LDR-FLIP
  Hdr,  // linear RGB, any range: HDR-FLIP
};

struct FlipOptions {
  double ppd = kFlipDefaultPpd;  // observer's pixels per degree of visual angle, (0, 1000]
  FlipInput input = FlipInput::Ldr;
};

struct FlipResult {
  int width = 0, height = 0;
  std::vector<float> map;  // FLIP per pixel, row-major, row 0 at the top, each in [0, 1]
  double mean = 0.0;
  // Weighted percentiles as NVIDIA's tool reports them (flipWeightedPercentile):
  // each value weighted by itself, so they tell where the error mass lies.
  double weightedMedian = 0.0, weightedQ1 = 0.0, weightedQ3 = 0.0;
  double min = 0.0, max = 0.0;
  std::int64_t nanPixels = 0;  // see the NaN policy above
  double ppd = kFlipDefaultPpd;
  FlipInput input = FlipInput::Ldr;
  // HDR-FLIP only: the exposure range (stops) and the number of exposures.
  double startExposure = 0.0, stopExposure = 0.0;
  int exposures = 0;
};

// FLIP of `test` against `reference` (the HDR exposure range comes from the
// reference). Throws InputError when the sizes differ or an image has fewer than
// 3 channels; std::invalid_argument unless 0 < ppd <= kFlipMaxPpd or when an
// image's pixel count does not match its size. Empty images give an empty map
// and 0 everywhere.
FlipResult computeFlip(const Image& test, const Image& reference, const FlipOptions& options = {});

// The weighted percentile of NVIDIA's FLIP tool: with the values sorted
// ascending, the first whose running sum exceeds p * (sum of all values); 0 when
// the sum is 0 (e.g. identical images). p in [0, 1].
double flipWeightedPercentile(std::vector<float> values, double p);

// {"mean", "weighted_median", "weighted_q1", "weighted_q3", "min", "max",
//  "nan_pixels", "ppd", "input": "ldr"|"hdr"} and, for HDR,
// "exposures": {"start", "stop", "count"}.
nlohmann::json toJson(const FlipResult& r);

// The magma colour map (matplotlib's, CC0, van der Walt & Smith; the map of the
// FLIP papers' error images), 18 control points from its 256-entry table,
// linearly interpolated. t is clamped to [0, 1] (NaN -> 0); magma(0) is near
// black (0.001462, 0.000466, 0.013866), magma(1) pale yellow (0.987053,
// 0.991438, 0.749504). Display (sRGB-encoded) colours, written to a PNG as they are.
std::array<float, 3> magma(double t);

// The FLIP error map as an RGBA image (alpha 1), each pixel magma(FLIP).
Image flipErrorImage(const FlipResult& r);

namespace flip {

// A three-channel image in planes (channel-major), row 0 at the top.
struct Planes {
  int width = 0, height = 0;
  std::array<std::vector<float>, 3> c;
  Planes() = default;
  Planes(int w, int h);
  std::size_t size() const { return static_cast<std::size_t>(width) * height; }
};

// sRGB display value -> linear (IEC 61966-2-1).
float srgbToLinear(float v);

// Linear RGB <-> XYZ (sRGB primaries, D65; white RGB (1, 1, 1) is the reference white).
std::array<float, 3> linearRgbToXyz(const std::array<float, 3>& rgb);
std::array<float, 3> xyzToLinearRgb(const std::array<float, 3>& xyz);
// XYZ <-> YyCxCz: Yy = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn), Cz = 200 (Y/Yn - Z/Zn).
std::array<float, 3> xyzToYcxcz(const std::array<float, 3>& xyz);
std::array<float, 3> ycxczToXyz(const std::array<float, 3>& ycxcz);
// XYZ -> CIELAB (same white).
std::array<float, 3> xyzToLab(const std::array<float, 3>& xyz);
// Hunt adjustment: a and b scaled by 0.01 L.
std::array<float, 3> huntAdjust(const std::array<float, 3>& lab);
// HyAB distance: |dL| + sqrt(da^2 + db^2).
float hyab(const std::array<float, 3>& x, const std::array<float, 3>& y);
// The colour difference mapped to [0, 1]: d^qc, then linear to pt below pc * cmax
// and linear from pt to 1 above it.
float redistributeColorError(float hyabDistance);

// One-dimensional filter taps (2 * radius + 1, centred).
struct ContrastSensitivityFilters {
  int radius = 0;
  // Achromatic (A), red-green (RG): normalized Gaussians; blue-yellow (BY): a sum
  // of two Gaussians as two separable terms, by1 (x) by1 + by2 (x) by2, whose
  // two-dimensional sum is 1.
  std::vector<float> a, rg, by1, by2;
};
// The contrast sensitivity functions in the spatial domain at `ppd`.
ContrastSensitivityFilters contrastSensitivityFilters(double ppd);

struct FeatureFilters {
  int radius = 0;
  // Gaussian (sum 1), its first and second derivatives (positive taps sum to 1,
  // negative ones to -1).
  std::vector<float> g, dg, ddg;
};
// The edge and point detectors at `ppd` (sigma = 0.5 * 0.082 degrees).
FeatureFilters featureFilters(double ppd);

// Linear RGB planes -> YyCxCz planes (in place).
Planes linearRgbToYcxczPlanes(Planes rgb);
// The colour pipeline on YyCxCz images: spatial filtering, then per pixel
// linear RGB (clamped), CIELAB, Hunt, HyAB and the redistribution.
std::vector<float> colorDifference(const Planes& testYcxcz, const Planes& referenceYcxcz,
                                   const ContrastSensitivityFilters& f);
// The feature pipeline on the achromatic channel (Yy + 16) / 116 in [0, 1]:
// (max(|edge_t - edge_r|, |point_t - point_r|) / sqrt(2)) ^ qf.
std::vector<float> featureDifference(const Planes& testYcxcz, const Planes& referenceYcxcz,
                                     const FeatureFilters& f);
// colour ^ (1 - feature), per pixel.
std::vector<float> combine(std::vector<float> colour, const std::vector<float>& feature);
// LDR-FLIP of two linear RGB images with values in [0, 1].
std::vector<float> ldrFlip(Planes testRgb, Planes referenceRgb, double ppd);

// The tone mapper of HDR-FLIP (ACES fit, with the 0.6 pre-exposure), per channel.
float toneMap(float v);
struct ExposureRange {
  double start = 0.0, stop = 0.0;
  int count = 2;
};
// From the reference's luminance (finite samples only). A reference whose
// median luminance is 0 (half the pixels black) would give an unbounded stop
// exposure: the median of its non-zero luminances is used instead; a black
// reference gives start = stop = 0.
ExposureRange exposureRange(const Planes& referenceRgb);
// HDR-FLIP: per pixel the largest LDR-FLIP over the exposures.
std::vector<float> hdrFlip(const Planes& testRgb, const Planes& referenceRgb, double ppd,
                           const ExposureRange& exposures);

}  // namespace flip
}  // namespace sb
