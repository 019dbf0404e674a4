#include "imaging/image.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <new>
#include <stdexcept>
#include <system_error>

#include "base/errors.h"
#include "imaging/oiio/oiio_api.h"

namespace sb {

namespace fs = std::filesystem;

Image::Image(int w, int h, int c, float fill) : width(w), height(h), channels(c) {
  if (w < 0 || h < 0 || c <= 0) {
    throw std::invalid_argument("Image: bad size " + std::to_string(w) + "x" + std::to_string(h) +
                                "x" + std::to_string(c));
  }
  pixels.assign(
      static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * static_cast<std::size_t>(c),
      fill);
}

std::size_t bytesPerSample(PixelType t) {
  switch (t) {
    case PixelType::UNorm8:
      return 1;
    case PixelType::Float32:
      return 4;
  }
  throw std::invalid_argument("bytesPerSample: unknown PixelType");
}

Image imageFromRows(const std::vector<std::uint8_t>& bytes, int w, int h, PixelType t,
                    int channels) {
  if (w <= 0 || h <= 0 || channels <= 0) {
    throw std::invalid_argument("imageFromRows: bad size " + std::to_string(w) + "x" +
                                std::to_string(h) + "x" + std::to_string(channels));
  }
  const std::size_t rowSamples = static_cast<std::size_t>(w) * static_cast<std::size_t>(channels);
  const std::size_t bps = bytesPerSample(t);
  const std::size_t expected = rowSamples * static_cast<std::size_t>(h) * bps;
  if (bytes.size() != expected) {
    throw std::invalid_argument("imageFromRows: got " + std::to_string(bytes.size()) +
                                " bytes, expected " + std::to_string(expected) + " for " +
                                std::to_string(w) + "x" + std::to_string(h) + "x" +
                                std::to_string(channels));
  }
  Image img(w, h, channels);
  for (int y = 0; y < h; ++y) {
    // Readback row (h - 1 - y) is the y-th row from the top.
    const std::size_t srcRow = static_cast<std::size_t>(h - 1 - y);
    const std::uint8_t* src = bytes.data() + srcRow * rowSamples * bps;
    float* dst = img.pixels.data() + static_cast<std::size_t>(y) * rowSamples;
    if (t == PixelType::UNorm8) {
      for (std::size_t i = 0; i < rowSamples; ++i) dst[i] = static_cast<float>(src[i]) / 255.0f;
    } else {
      std::memcpy(dst, src, rowSamples * sizeof(float));
    }
  }
  return img;
}

namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return ext;
}

std::string inQuotes(const std::string& s) { return "'" + s + "'"; }

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw InputError("cannot write image " + inQuotes(path) + ": " + problem);
}

[[noreturn]] void failReading(const std::string& path, const std::string& problem) {
  throw InputError("cannot read image " + inQuotes(path) + ": " + problem);
}

template <typename T>
std::vector<T> quantize(const std::vector<float>& src, float maxCode) {
  std::vector<T> out(src.size());
  for (std::size_t i = 0; i < src.size(); ++i) {
    float v = src[i];
    if (std::isnan(v)) v = 0.0f;  // NaN has no code; 0 like a GPU UNORM conversion
    v = std::clamp(v, 0.0f, 1.0f);
    out[i] = static_cast<T>(std::lround(v * maxCode));
  }
  return out;
}

// Removes the temporary file unless released.
struct TempFile {
  std::string path;
  bool keep = false;
  ~TempFile() {
    if (!keep && !path.empty()) {
      std::error_code ec;
      fs::remove(path, ec);
    }
  }
};

}  // namespace

namespace {
void writeImageFile(const Image& img, const std::string& path, ImageBitDepth depth) {
  if (img.width <= 0 || img.height <= 0 || img.channels <= 0 ||
      img.pixels.size() != static_cast<std::size_t>(img.width) *
                               static_cast<std::size_t>(img.height) *
                               static_cast<std::size_t>(img.channels)) {
    throw std::invalid_argument("writeImage " + inQuotes(path) + ": empty or inconsistent image " +
                                std::to_string(img.width) + "x" + std::to_string(img.height) + "x" +
                                std::to_string(img.channels) + " with " +
                                std::to_string(img.pixels.size()) + " samples");
  }

  // --- format and sample type from the extension and the requested depth ---
  const std::string ext = lowerExtension(path);
  std::string format;
  if (ext == ".png") {
    format = "png";
    if (depth == ImageBitDepth::Default) depth = ImageBitDepth::U8;
    if (depth != ImageBitDepth::U8 && depth != ImageBitDepth::U16) {
      fail(path, "PNG holds 8- or 16-bit integers only (use .exr for float)");
    }
    if (img.channels > 4) {
      fail(path, "PNG holds 1 to 4 channels, image has " + std::to_string(img.channels));
    }
  } else if (ext == ".exr") {
    format = "openexr";
    if (depth == ImageBitDepth::Default) depth = ImageBitDepth::F32;
    if (depth != ImageBitDepth::F16 && depth != ImageBitDepth::F32) {
      fail(path, "EXR is written as half or float only (use .png for 8/16-bit)");
    }
  } else {
    fail(path, "unknown image extension " + inQuotes(ext) + " (use .png or .exr)");
  }

  // --- temporary file in the same folder (so rename is atomic) ---
  const fs::path target(path);
  fs::path folder = target.parent_path();
  if (folder.empty()) folder = ".";
  {
    std::error_code ec;
    if (!fs::exists(folder, ec))
      fail(path, "folder " + inQuotes(folder.string()) + " does not exist");
    if (!fs::is_directory(folder, ec)) fail(path, inQuotes(folder.string()) + " is not a folder");
    if (fs::is_directory(target, ec)) fail(path, "it is a folder");
  }
  std::string tmpl = path + ".tmp-XXXXXX";
  std::vector<char> tmplBuf(tmpl.begin(), tmpl.end());
  tmplBuf.push_back('\0');
  const int fd = ::mkstemp(tmplBuf.data());
  if (fd < 0) {
    const int err = errno;
    fail(path,
         "cannot create a file in folder " + inQuotes(folder.string()) + ": " + std::strerror(err));
  }
  TempFile tmp{std::string(tmplBuf.data())};
  ::fchmod(fd, 0644);  // mkstemp makes 0600; image files are for sharing
  ::close(fd);

  // --- encode ---
  std::string error;
  const auto& io = oiio::api();
  if (depth == ImageBitDepth::U8) {
    const auto data = quantize<std::uint8_t>(img.pixels, 255.0f);
    error = io.write(tmp.path, format, img.width, img.height, img.channels, 0, data.data());
  } else if (depth == ImageBitDepth::U16) {
    const auto data = quantize<std::uint16_t>(img.pixels, 65535.0f);
    error = io.write(tmp.path, format, img.width, img.height, img.channels, 1, data.data());
  } else {
    const int type = depth == ImageBitDepth::F16 ? 2 : 3;
    error =
        io.write(tmp.path, format, img.width, img.height, img.channels, type, img.pixels.data());
  }
  if (!error.empty()) fail(path, error);

  // --- publish ---
  std::error_code ec;
  fs::rename(tmp.path, target, ec);
  if (ec) fail(path, "cannot rename " + inQuotes(tmp.path) + " into place: " + ec.message());
  tmp.keep = true;
}
}  // namespace

void writeImage(const Image& img, const std::string& path, ImageBitDepth depth) {
  try {
    writeImageFile(img, path, depth);
  } catch (const std::bad_alloc&) {
    // The temporary file is already gone (TempFile); the target is untouched.
    throw OutOfMemoryError("out of memory writing image " + path + " (" +
                           std::to_string(img.width) + "x" + std::to_string(img.height) + "x" +
                           std::to_string(img.channels) + ", " +
                           std::to_string(img.pixels.size() * sizeof(float)) +
                           " bytes of samples): a host allocation failed; nothing was written");
  }
}

void loadImageModule() { (void)oiio::api(); }

Image readImage(const std::string& path) {
  auto failRead = [&path](const std::string& problem) { failReading(path, problem); };
  std::error_code ec;
  if (!fs::exists(path, ec)) failRead("no such file");
  if (fs::is_directory(path, ec)) failRead("it is a folder");

  int w = 0, h = 0, nch = 0;
  std::vector<float> raw;
  if (const std::string e = oiio::api().read(path, w, h, nch, raw); !e.empty()) failRead(e);

  Image img(w, h, 4);
  const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  for (std::size_t i = 0; i < n; ++i) {
    const float* s = raw.data() + i * static_cast<std::size_t>(nch);
    float* d = img.pixels.data() + i * 4;
    switch (nch) {
      case 1:
        d[0] = d[1] = d[2] = s[0];
        d[3] = 1.0f;
        break;
      case 2:
        d[0] = d[1] = d[2] = s[0];
        d[3] = s[1];
        break;
      case 3:
        d[0] = s[0];
        d[1] = s[1];
        d[2] = s[2];
        d[3] = 1.0f;
        break;
      default:
        std::copy(s, s + 4, d);
        break;
    }
  }
  return img;
}

}  // namespace sb
