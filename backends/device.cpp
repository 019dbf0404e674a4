#include "backends/device.h"

namespace sb {

std::size_t bytesPerPixel(Format f) {
  switch (f) {
    case Format::RGBA8:
      return 4;
    case Format::RGBA16F:
      return 8;
    case Format::RGBA32F:
      return 16;
    case Format::R32F:
      return 4;
    case Format::RG32F:
      return 8;
    case Format::R32UI:
      return 4;
    case Format::RGBA32UI:
      return 16;
    case Format::Depth32F:
      return 4;
  }
  return 0;
}

bool isDepthFormat(Format f) { return f == Format::Depth32F; }

bool isIntegerFormat(Format f) { return f == Format::R32UI || f == Format::RGBA32UI; }

const char* formatName(Format f) {
  switch (f) {
    case Format::RGBA8:
      return "RGBA8";
    case Format::RGBA16F:
      return "RGBA16F";
    case Format::RGBA32F:
      return "RGBA32F";
    case Format::R32F:
      return "R32F";
    case Format::RG32F:
      return "RG32F";
    case Format::R32UI:
      return "R32UI";
    case Format::RGBA32UI:
      return "RGBA32UI";
    case Format::Depth32F:
      return "Depth32F";
  }
  return "?";
}

}  // namespace sb
