// What a frame is rendered for: a closed set. The renderer keeps the passes
// these need (render/frame/renderer.h); kOutputNames names them in messages.
#pragma once

#include <cstddef>
#include <iterator>
#include <set>
#include <string>

namespace sb {

enum class Output {
  Color,       // the shaded image
  Visibility,  // the visibility image (render/outputs/visibility)
  Probe,       // the shadow technique's visibility at the probe points (render/outputs/probe)
};
using Outputs = std::set<Output>;

// By the enum's value.
inline constexpr const char* kOutputNames[] = {"color", "visibility", "probe"};
static_assert(std::size(kOutputNames) == static_cast<std::size_t>(Output::Probe) + 1);

inline std::string outputName(Output output) {
  return kOutputNames[static_cast<std::size_t>(output)];
}

}  // namespace sb
