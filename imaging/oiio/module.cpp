// libsb_oiio.so: every OpenImageIO call of strandbench, behind the plain functions of
// imaging/oiio/oiio_api.h, so that only a process that reads or writes an image file loads
// OpenImageIO (imaging/oiio/loader.cpp).
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "imaging/oiio/oiio_api.h"

namespace sb::oiio {

struct Canvas {
  OIIO::ImageBuf buf;
};

namespace {

// OIIO's error text, without trailing newlines.
std::string errorText(const std::string& fromObject) {
  std::string e = fromObject.empty() ? OIIO::geterror() : fromObject;
  while (!e.empty() && (e.back() == '\n' || e.back() == ' ')) e.pop_back();
  return e.empty() ? std::string("unknown OpenImageIO error") : e;
}

std::string write(const std::string& path, const std::string& format, int w, int h, int channels,
                  int type, const void* samples) {
  static const OIIO::TypeDesc kFileTypes[] = {OIIO::TypeDesc::UINT8, OIIO::TypeDesc::UINT16,
                                              OIIO::TypeDesc::HALF, OIIO::TypeDesc::FLOAT};
  static const OIIO::TypeDesc kDataTypes[] = {OIIO::TypeDesc::UINT8, OIIO::TypeDesc::UINT16,
                                              OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::FLOAT};
  OIIO::ImageSpec spec(w, h, channels, kFileTypes[type]);
  switch (channels) {
    case 1:
      spec.channelnames = {"Y"};
      spec.alpha_channel = -1;
      break;
    case 2:
      spec.channelnames = {"Y", "A"};
      spec.alpha_channel = 1;
      break;
    case 3:
      spec.channelnames = {"R", "G", "B"};
      spec.alpha_channel = -1;
      break;
    case 4:
      spec.channelnames = {"R", "G", "B", "A"};
      spec.alpha_channel = 3;
      break;
    default:
      break;  // OIIO's default names
  }
  // Samples are stored as given: no premultiplication / unpremultiplication.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  if (format == "openexr") {
    spec.attribute("compression", "zip");
    // OIIO's EXR writer stores the current time as capDate unless DateTime is
    // given; an empty one keeps the bytes independent of when they were written.
    spec.attribute("DateTime", "");
  }
  auto out = OIIO::ImageOutput::create(format);
  if (!out) return "no OpenImageIO writer for " + format + ": " + errorText("");
  if (!out->open(path, spec)) return errorText(out->geterror());
  if (!out->write_image(kDataTypes[type], samples)) {
    std::string e = errorText(out->geterror());
    out->close();
    return e;
  }
  if (!out->close()) return errorText(out->geterror());
  return "";
}

std::string read(const std::string& path, int& w, int& h, int& channels,
                 std::vector<float>& samples) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // give samples as stored
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) return errorText("");
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.deep) return "deep images are not supported";
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) return "empty image";
  if (spec.depth > 1) return "volume images are not supported";
  w = spec.width;
  h = spec.height;
  channels = spec.nchannels;
  samples.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) *
                 static_cast<std::size_t>(channels));
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, samples.data()))
    return errorText(in->geterror());
  in->close();
  return "";
}

Canvas* canvasCreate(int w, int h) {
  auto* c = new Canvas{OIIO::ImageBuf(OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT))};
  OIIO::ImageBufAlgo::fill(c->buf, {1.0f, 1.0f, 1.0f});
  return c;
}

void canvasFree(Canvas* c) { delete c; }

void canvasFill(Canvas* c, int x0, int x1, int y0, int y1, float r, float g, float b) {
  OIIO::ImageBufAlgo::fill(c->buf, {r, g, b}, OIIO::ROI(x0, x1, y0, y1, 0, 1, 0, 3));
}

bool canvasText(Canvas* c, int x, int y, const std::string& text, int size, float r, float g,
                float b) {
  const float colour[] = {r, g, b};
  const bool ok = OIIO::ImageBufAlgo::render_text(c->buf, x, y, text, size, "DejaVuSans",
                                                  OIIO::cspan<float>(colour, 3));
  if (!ok) (void)c->buf.geterror();
  return ok;
}

bool canvasPaste(Canvas* c, const std::string& file, int x, int y, int tile) {
  OIIO::ImageBuf src(file);
  if (!src.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
    (void)src.geterror();
    return false;
  }
  const OIIO::ROI box(0, tile, 0, tile, 0, 1, 0, 3);
  OIIO::ImageBuf rgb = OIIO::ImageBufAlgo::channels(src, 3, {0, 1, 2});
  OIIO::ImageBuf fitted = OIIO::ImageBufAlgo::fit(rgb, "", 0.0f, "letterbox", false, box);
  if (fitted.has_error()) {
    (void)fitted.geterror();
    return false;
  }
  return OIIO::ImageBufAlgo::paste(c->buf, x, y, 0, 0, fitted);
}

void canvasPixels(Canvas* c, float* out) {
  const OIIO::ImageSpec& s = c->buf.spec();
  c->buf.get_pixels(OIIO::ROI(0, s.width, 0, s.height, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT, out);
}

const Api kApi = {write,      read,       canvasCreate, canvasFree,
                  canvasFill, canvasText, canvasPaste,  canvasPixels};

}  // namespace
}  // namespace sb::oiio

extern "C" __attribute__((visibility("default"))) const sb::oiio::Api* sb_oiio_api() {
  return &sb::oiio::kApi;
}
