// Image-space error metrics, diff heatmaps and `strandbench compare A B`.
//
// NaN policy (a NaN must never make two images look alike):
//  - A pixel whose difference is NaN in any compared channel (NaN in either
//    image, or inf - inf) is a "NaN pixel": it is counted in nanPixels and in
//    pixelsOver / fractionOver, and when there is at least one, rmse = +inf,
//    psnr = -inf and maxAbs = +inf.
//  - An infinite difference (inf vs a finite value) is simply infinite: it makes
//    rmse and maxAbs +inf and psnr -inf.
//  - SSIM is NaN (JSON null) when any compared sample is NaN or infinite; a
//    test "ssim >= x" is then false.
//
// JSON (toJson, compare): JSON has no infinity or NaN, so a non-finite number is
// written as null. "identical": true says the images are equal in the compared
// channels (rmse 0, psnr +inf); psnr null with "identical": false means
// psnr -inf (NaN or infinite differences, see "nan_pixels").
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "imaging/flip.h"
#include "imaging/image.h"

namespace sb {

struct ImageError {
  double rmse = 0.0;          // sqrt(mean over pixels x channels of (a - b)^2)
  double psnr = 0.0;          // 20 log10(1 / rmse), peak 1.0; +inf when rmse == 0
  double maxAbs = 0.0;        // max |a - b| over pixels x channels
  double fractionOver = 0.0;  // pixelsOver / (width * height)
  int width = 0, height = 0;
  int channels = 0;             // channels compared (0 .. channels-1)
  std::int64_t pixelsOver = 0;  // pixels whose max channel |a - b| > threshold, or NaN
  std::int64_t nanPixels = 0;   // pixels with a NaN difference in a compared channel
  // Structural similarity (Wang, Bovik, Sheikh & Simoncelli 2004): Gaussian
  // window 11x11, sigma 1.5, K1 = 0.01, K2 = 0.03, dynamic range L = 1; the
  // SSIM map's mean over every window position that lies wholly inside the
  // image (no padding), per compared channel, averaged over those channels.
  // 1 for identical images; below 1 for any difference. Images narrower or
  // shorter than 11 pixels use the largest odd window that fits (same sigma,
  // weights renormalized). NaN when a compared sample is NaN or infinite.
  double ssim = 1.0;
  bool identical() const { return rmse == 0.0 && nanPixels == 0; }
};

// Compares channels [0, channels) of a and b (RGB by default: alpha excluded),
// values as stored (no clamping). A pixel is over the threshold when its largest
// channel difference exceeds threshold * (1 + 1e-4): the small relative margin
// keeps float rounding of 8-bit codes (k/255 stored as float) from turning an
// exactly-one-code difference into a failure at the default threshold of one
// 8-bit code; threshold 0 is exact.
// Throws InputError when the sizes differ (message has both sizes) or an image
// has fewer than `channels` channels; std::invalid_argument when channels < 1 or
// an image's pixel count does not match its size.
ImageError compareImages(const Image& a, const Image& b, double threshold = 1.0 / 255.0,
                         int channels = 3);

// A banding measure: the RMSE of the luminance difference a - b (Rec. 709 weights on RGB)
// after a (2 radius + 1)^2 box filter (clamped at the borders). Coherent errors (stripes,
// stair steps, layering) survive the filter; per-pixel noise of zero mean averages out, so
// jittered sampling that trades banding for noise scores lower while plain RMSE can score it
// higher. 0 for identical images. Throws InputError when the sizes differ or an image has
// fewer than 3 channels.
double bandingMeasure(const Image& a, const Image& b, int radius = 3);

// {"width", "height", "channels", "rmse", "psnr", "max_abs", "ssim",
//  "fraction_over", "pixels_over", "nan_pixels", "identical"}; non-finite
// numbers -> null.
nlohmann::json toJson(const ImageError& e);

// A colour map of evenly spaced RGB control points, linearly interpolated; t
// is clamped to [0, 1] (NaN -> 0). viridis below and FLIP's magma (flip.h).
enum class ColourMap { Viridis, Magma };
std::array<float, 3> colourMap(ColourMap map, double t);

// The viridis colour map (matplotlib's, 18 control points from its 256-entry
// table, linearly interpolated). t is clamped to [0, 1]; viridis(0) is dark
// purple (0.267004, 0.004874, 0.329415), viridis(1) yellow (0.993248, 0.906157,
// 0.143936). Values are display (sRGB-encoded) colours, meant to be written to a
// PNG as they are.
std::array<float, 3> viridis(double t);

// Heatmap of per-pixel max |a - b| over channels [0, channels): difference 0 ->
// viridis(0), difference >= scale -> viridis(1), linear in between; a NaN pixel is
// magenta (1, 0, 1), which viridis never produces. RGBA, alpha 1, same size as
// the inputs. Throws like compareImages, and std::invalid_argument unless scale > 0.
Image diffHeatmap(const Image& a, const Image& b, double scale, int channels = 3);

// `strandbench compare A B`: reads both images (readImage), compares RGB, prints
// one JSON object to `out`:
//   {"a", "b", "width", "height", "channels", "threshold", "rmse", "psnr",
//    "max_abs", "ssim", "fraction_over", "pixels_over", "nan_pixels", "identical",
//    "flip": {FLIP of A against B at `ppd`, imaging/flip.h toJson}}
// and returns 0. B is FLIP's reference; FLIP is HDR-FLIP when B is an EXR file
// (linear values), else LDR-FLIP (display values, as a PNG holds). With a
// `flipMap` path, also writes FLIP's magma error map there. On InputError
// (unreadable file, size mismatch, unwritable map) prints
// "strandbench compare: <message>" to `err` and returns 2.
int runCompareCommand(const std::string& a, const std::string& b, std::ostream& out,
                      std::ostream& err, double threshold = 1.0 / 255.0,
                      double ppd = kFlipDefaultPpd, const std::string& flipMap = "");

// Visibility error: technique against exact light visibility, per pixel, over
// the pixels where both images see a surface (values >= 0; -1 marks none).
struct VisibilityError {
  double rmse = 0, max = 0;
  std::size_t pixels = 0;
};
VisibilityError compareVisibility(const std::vector<float>& a, const std::vector<float>& b);

}  // namespace sb
