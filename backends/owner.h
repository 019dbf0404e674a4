// Who a device resource is for: a closed set. Memory is reported and refused
// by owner (render --json "resources"[].owner and "memory"; the refusal's "By
// owner" and its advice). kOwnerNames is the one name table (the JSON's and
// the messages' words).
#pragma once

#include <cstddef>
#include <iterator>
#include <string>

namespace sb {

enum class Owner {
  None,    // not said (a default-made description)
  Scene,   // the strands, the mesh and their buffers
  Shadow,  // the shadow technique's
  Oit,     // the transparency technique's
  Frame,   // the frame's targets and the renderer's own
  Host,    // host memory (the image read back), counted in budgets
  View,    // the viewer's display and overlay
  Test,    // made by a test
};

// By the enum's value; kOwnerNames[Owner::None] is "".
inline constexpr const char* kOwnerNames[] = {"",      "scene", "shadow", "oit",
                                              "frame", "host",  "view",   "test"};
static_assert(std::size(kOwnerNames) == static_cast<std::size_t>(Owner::Test) + 1);

inline std::string ownerName(Owner owner) { return kOwnerNames[static_cast<std::size_t>(owner)]; }

}  // namespace sb
