#include "imaging/metrics.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <ostream>
#include <stdexcept>
#include <vector>

#include "base/errors.h"
#include "imaging/flip.h"

namespace sb {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string sizeText(const Image& img) {
  return std::to_string(img.width) + "x" + std::to_string(img.height);
}

void checkConsistent(const Image& img, const char* which) {
  const std::size_t expected = static_cast<std::size_t>(std::max(img.width, 0)) *
                               static_cast<std::size_t>(std::max(img.height, 0)) *
                               static_cast<std::size_t>(std::max(img.channels, 0));
  if (img.pixels.size() != expected) {
    throw std::invalid_argument(std::string("image ") + which + " (" + sizeText(img) + "x" +
                                std::to_string(img.channels) + ") has " +
                                std::to_string(img.pixels.size()) + " samples, expected " +
                                std::to_string(expected));
  }
}

void checkComparable(const Image& a, const Image& b, int channels) {
  if (channels < 1) {
    throw std::invalid_argument("compare: channels must be at least 1, got " +
                                std::to_string(channels));
  }
  checkConsistent(a, "a");
  checkConsistent(b, "b");
  if (a.width != b.width || a.height != b.height) {
    throw InputError("image sizes differ: " + sizeText(a) + " vs " + sizeText(b));
  }
  if (a.channels < channels || b.channels < channels) {
    throw InputError("cannot compare " + std::to_string(channels) + " channels: images have " +
                     std::to_string(a.channels) + " and " + std::to_string(b.channels));
  }
}

// Largest |a - b| over channels [0, channels) of pixel i; NaN if any is NaN.
double pixelMaxDiff(const Image& a, const Image& b, std::size_t i, int channels) {
  const float* pa = a.pixels.data() + i * static_cast<std::size_t>(a.channels);
  const float* pb = b.pixels.data() + i * static_cast<std::size_t>(b.channels);
  double m = 0.0;
  for (int c = 0; c < channels; ++c) {
    const double d = std::fabs(static_cast<double>(pa[c]) - static_cast<double>(pb[c]));
    if (std::isnan(d)) return std::numeric_limits<double>::quiet_NaN();
    m = std::max(m, d);
  }
  return m;
}

nlohmann::json number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

// The colour maps, each 18 control points of matplotlib's 256-entry table
// (CC0, van der Walt & Smith) at entries 0, 15, 30, ..., 255, in the order of
// ColourMap: viridis, then magma (FLIP's error map).
constexpr int kColourMapPoints = 18;
constexpr float kColourMaps[2][kColourMapPoints][3] = {
    {
        {0.267004f, 0.004874f, 0.329415f},  // 0
        {0.281924f, 0.089666f, 0.412415f},  // 15
        {0.280255f, 0.165693f, 0.476498f},  // 30
        {0.263663f, 0.237631f, 0.518762f},  // 45
        {0.237441f, 0.305202f, 0.541921f},  // 60
        {0.208623f, 0.367752f, 0.552675f},  // 75
        {0.182256f, 0.426184f, 0.557120f},  // 90
        {0.159194f, 0.482237f, 0.558073f},  // 105
        {0.137770f, 0.537492f, 0.554906f},  // 120
        {0.121148f, 0.592739f, 0.544641f},  // 135
        {0.128087f, 0.647749f, 0.523491f},  // 150
        {0.180653f, 0.701402f, 0.488189f},  // 165
        {0.274149f, 0.751988f, 0.436601f},  // 180
        {0.395174f, 0.797475f, 0.367757f},  // 195
        {0.535621f, 0.835785f, 0.281908f},  // 210
        {0.688944f, 0.865448f, 0.182725f},  // 225
        {0.845561f, 0.887322f, 0.099702f},  // 240
        {0.993248f, 0.906157f, 0.143936f},  // 255
    },
    {
        {0.001462f, 0.000466f, 0.013866f},  // 0
        {0.035520f, 0.028397f, 0.125209f},  // 15
        {0.102815f, 0.063010f, 0.257854f},  // 30
        {0.191460f, 0.064818f, 0.396152f},  // 45
        {0.291366f, 0.064553f, 0.475462f},  // 60
        {0.384299f, 0.097855f, 0.501002f},  // 75
        {0.475780f, 0.134577f, 0.507921f},  // 90
        {0.569172f, 0.167454f, 0.504105f},  // 105
        {0.664915f, 0.198075f, 0.488836f},  // 120
        {0.761077f, 0.231214f, 0.460162f},  // 135
        {0.852126f, 0.276106f, 0.418573f},  // 150
        {0.925937f, 0.346844f, 0.374959f},  // 165
        {0.969680f, 0.446936f, 0.360311f},  // 180
        {0.989363f, 0.557873f, 0.391671f},  // 195
        {0.996580f, 0.668256f, 0.456192f},  // 210
        {0.996727f, 0.776795f, 0.541039f},  // 225
        {0.992440f, 0.884330f, 0.640099f},  // 240
        {0.987053f, 0.991438f, 0.749504f},  // 255
    },
};

// Normalized 1-D Gaussian weights, sigma 1.5, `size` taps (odd) centred.
std::vector<double> gaussianWindow(int size) {
  constexpr double kSigma = 1.5;
  std::vector<double> w(static_cast<std::size_t>(size));
  const int half = size / 2;
  double sum = 0.0;
  for (int i = 0; i < size; ++i) {
    const double d = i - half;
    w[static_cast<std::size_t>(i)] = std::exp(-d * d / (2.0 * kSigma * kSigma));
    sum += w[static_cast<std::size_t>(i)];
  }
  for (double& v : w) v /= sum;
  return w;
}

// Mean SSIM of channel c over all valid window positions (Wang et al. 2004),
// with the separable Gaussian window applied to a, b, a^2, b^2 and ab.
double channelSsim(const Image& a, const Image& b, int c, const std::vector<double>& w) {
  constexpr double kC1 = 0.01 * 0.01, kC2 = 0.03 * 0.03;  // (K L)^2, L = 1
  const int k = static_cast<int>(w.size());
  const int width = a.width, height = a.height;
  const int vw = width - k + 1, vh = height - k + 1;  // valid positions
  // Horizontal pass: for every row and valid x, the five weighted sums.
  constexpr int kMoments = 5;  // a, b, a^2, b^2, ab
  std::vector<double> rows(static_cast<std::size_t>(height) * static_cast<std::size_t>(vw) *
                           kMoments);
  for (int y = 0; y < height; ++y) {
    for (int x0 = 0; x0 < vw; ++x0) {
      double m[kMoments] = {0, 0, 0, 0, 0};
      for (int i = 0; i < k; ++i) {
        const double wa = w[static_cast<std::size_t>(i)];
        const double va = a.at(x0 + i, y, c), vb = b.at(x0 + i, y, c);
        m[0] += wa * va;
        m[1] += wa * vb;
        m[2] += wa * va * va;
        m[3] += wa * vb * vb;
        m[4] += wa * va * vb;
      }
      double* out = rows.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(vw) +
                                   static_cast<std::size_t>(x0)) *
                                      kMoments;
      for (int j = 0; j < kMoments; ++j) out[j] = m[j];
    }
  }
  // Vertical pass and the SSIM map, summed.
  double sum = 0.0;
  for (int y0 = 0; y0 < vh; ++y0) {
    for (int x0 = 0; x0 < vw; ++x0) {
      double m[kMoments] = {0, 0, 0, 0, 0};
      for (int i = 0; i < k; ++i) {
        const double wv = w[static_cast<std::size_t>(i)];
        const double* in =
            rows.data() + (static_cast<std::size_t>(y0 + i) * static_cast<std::size_t>(vw) +
                           static_cast<std::size_t>(x0)) *
                              kMoments;
        for (int j = 0; j < kMoments; ++j) m[j] += wv * in[j];
      }
      const double muA = m[0], muB = m[1];
      const double varA = m[2] - muA * muA, varB = m[3] - muB * muB, cov = m[4] - muA * muB;
      sum += ((2.0 * muA * muB + kC1) * (2.0 * cov + kC2)) /
             ((muA * muA + muB * muB + kC1) * (varA + varB + kC2));
    }
  }
  return sum / (static_cast<double>(vw) * static_cast<double>(vh));
}

// Mean SSIM over channels [0, channels); NaN if any compared sample is not finite.
double meanSsim(const Image& a, const Image& b, int channels) {
  if (a.width <= 0 || a.height <= 0) return 1.0;
  const std::size_t n = static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height);
  for (std::size_t i = 0; i < n; ++i) {
    for (int c = 0; c < channels; ++c) {
      if (!std::isfinite(
              a.pixels[i * static_cast<std::size_t>(a.channels) + static_cast<std::size_t>(c)]) ||
          !std::isfinite(
              b.pixels[i * static_cast<std::size_t>(b.channels) + static_cast<std::size_t>(c)])) {
        return std::numeric_limits<double>::quiet_NaN();
      }
    }
  }
  int size = std::min({11, a.width, a.height});
  if (size % 2 == 0) --size;
  const std::vector<double> w = gaussianWindow(size);
  double sum = 0.0;
  for (int c = 0; c < channels; ++c) sum += channelSsim(a, b, c, w);
  return sum / channels;
}

// A file FLIP reads as linear HDR values (OpenEXR), by its extension.
bool isExr(const std::string& path) {
  std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return ext == ".exr";
}

}  // namespace

double bandingMeasure(const Image& a, const Image& b, int radius) {
  if (a.width != b.width || a.height != b.height)
    throw InputError("banding: images differ in size (" + std::to_string(a.width) + "x" +
                     std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                     std::to_string(b.height) + ")");
  if (a.channels < 3 || b.channels < 3) throw InputError("banding: an image has no RGB");
  const int w = a.width, h = a.height;
  if (w <= 0 || h <= 0) return 0.0;
  // Summed-area table of the luminance difference.
  std::vector<double> sat(std::size_t(w + 1) * std::size_t(h + 1), 0.0);
  auto S = [&](int x, int y) -> double& { return sat[std::size_t(y) * std::size_t(w + 1) + x]; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double d = 0.0;
      const double weights[3] = {0.2126, 0.7152, 0.0722};
      for (int c = 0; c < 3; ++c) d += weights[c] * (double(a.at(x, y, c)) - b.at(x, y, c));
      S(x + 1, y + 1) = d + S(x, y + 1) + S(x + 1, y) - S(x, y);
    }
  double sum = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int x0 = std::max(x - radius, 0), x1 = std::min(x + radius + 1, w);
      const int y0 = std::max(y - radius, 0), y1 = std::min(y + radius + 1, h);
      const double box =
          (S(x1, y1) - S(x0, y1) - S(x1, y0) + S(x0, y0)) / double((x1 - x0) * (y1 - y0));
      sum += box * box;
    }
  return std::sqrt(sum / double(w) / double(h));
}

ImageError compareImages(const Image& a, const Image& b, double threshold, int channels) {
  checkComparable(a, b, channels);
  ImageError e;
  e.width = a.width;
  e.height = a.height;
  e.channels = channels;
  const double overLimit = threshold * (1.0 + 1e-4);
  const std::size_t n = static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height);
  double sumSq = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const float* pa = a.pixels.data() + i * static_cast<std::size_t>(a.channels);
    const float* pb = b.pixels.data() + i * static_cast<std::size_t>(b.channels);
    double pixMax = 0.0;
    bool nan = false;
    for (int c = 0; c < channels; ++c) {
      const double d = std::fabs(static_cast<double>(pa[c]) - static_cast<double>(pb[c]));
      if (std::isnan(d)) {
        nan = true;
        continue;
      }
      sumSq += d * d;
      pixMax = std::max(pixMax, d);
    }
    e.maxAbs = std::max(e.maxAbs, pixMax);
    if (nan) {
      ++e.nanPixels;
      ++e.pixelsOver;
    } else if (pixMax > overLimit) {
      ++e.pixelsOver;
    }
  }
  if (n == 0) {
    e.rmse = 0.0;
  } else if (e.nanPixels > 0) {
    e.rmse = kInf;
    e.maxAbs = kInf;
  } else {
    e.rmse = std::sqrt(sumSq / (static_cast<double>(n) * channels));
  }
  e.psnr = e.rmse == 0.0 ? kInf : 20.0 * std::log10(1.0 / e.rmse);
  e.fractionOver = n == 0 ? 0.0 : static_cast<double>(e.pixelsOver) / static_cast<double>(n);
  e.ssim = meanSsim(a, b, channels);
  return e;
}

nlohmann::json toJson(const ImageError& e) {
  return nlohmann::json{{"width", e.width},
                        {"height", e.height},
                        {"channels", e.channels},
                        {"rmse", number(e.rmse)},
                        {"psnr", number(e.psnr)},
                        {"max_abs", number(e.maxAbs)},
                        {"ssim", number(e.ssim)},
                        {"fraction_over", e.fractionOver},
                        {"pixels_over", e.pixelsOver},
                        {"nan_pixels", e.nanPixels},
                        {"identical", e.identical()}};
}

std::array<float, 3> colourMap(ColourMap map, double t) {
  const auto& points = kColourMaps[static_cast<int>(map)];
  if (std::isnan(t)) t = 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const double x = t * (kColourMapPoints - 1);
  const int i = std::min(static_cast<int>(x), kColourMapPoints - 2);
  const double f = x - i;
  std::array<float, 3> rgb{};
  for (int c = 0; c < 3; ++c) {
    const double lo = points[i][c], hi = points[i + 1][c];
    rgb[static_cast<std::size_t>(c)] = static_cast<float>(lo + (hi - lo) * f);
  }
  return rgb;
}

std::array<float, 3> viridis(double t) { return colourMap(ColourMap::Viridis, t); }

Image diffHeatmap(const Image& a, const Image& b, double scale, int channels) {
  if (!(scale > 0.0) || !std::isfinite(scale)) {
    throw std::invalid_argument("diffHeatmap: scale must be a positive finite number, got " +
                                std::to_string(scale));
  }
  checkComparable(a, b, channels);
  Image out(a.width, a.height, 4, 1.0f);
  const std::size_t n = static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height);
  for (std::size_t i = 0; i < n; ++i) {
    const double d = pixelMaxDiff(a, b, i, channels);
    float* o = out.pixels.data() + i * 4;
    if (std::isnan(d)) {
      o[0] = 1.0f;
      o[1] = 0.0f;
      o[2] = 1.0f;
    } else {
      const auto rgb = viridis(d / scale);
      o[0] = rgb[0];
      o[1] = rgb[1];
      o[2] = rgb[2];
    }
    o[3] = 1.0f;
  }
  return out;
}

int runCompareCommand(const std::string& a, const std::string& b, std::ostream& out,
                      std::ostream& err, double threshold, double ppd, const std::string& flipMap) {
  try {
    const Image ia = readImage(a);
    const Image ib = readImage(b);
    if (ia.width != ib.width || ia.height != ib.height) {
      throw InputError("image sizes differ: '" + a + "' is " + sizeText(ia) + ", '" + b + "' is " +
                       sizeText(ib));
    }
    const ImageError e = compareImages(ia, ib, threshold, 3);
    FlipOptions flipOptions;
    flipOptions.ppd = ppd;
    flipOptions.input = isExr(b) ? FlipInput::Hdr : FlipInput::Ldr;
    const FlipResult flip = computeFlip(ia, ib, flipOptions);
    if (!flipMap.empty()) writeImage(flipErrorImage(flip), flipMap);
    nlohmann::json j{{"a", a}, {"b", b}, {"threshold", threshold}};
    j.update(toJson(e));
    j["flip"] = toJson(flip);
    out << j.dump(2) << "\n";
    return 0;
  } catch (const InputError& ex) {
    err << "strandbench compare: " << ex.what() << "\n";
    return 2;
  }
}

VisibilityError compareVisibility(const std::vector<float>& a, const std::vector<float>& b) {
  VisibilityError e;
  double sq = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    if (!(a[i] >= 0.0f) || !(b[i] >= 0.0f)) continue;
    const double d = std::abs(double(a[i]) - double(b[i]));
    sq += d * d;
    e.max = std::max(e.max, d);
    ++e.pixels;
  }
  e.rmse = e.pixels ? std::sqrt(sq / double(e.pixels)) : 0.0;
  return e;
}

}  // namespace sb
