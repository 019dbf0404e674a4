// The meshes `mesh=` takes (a scene's opaque mesh, the fur scene's base mesh) beyond OBJ
// (loadObj and parseObj, scenes/scene.h). They throw InputError naming the file and the
// problem, as the strand loaders do.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "scenes/scene.h"

namespace sb {

// A mesh by extension: .obj, .ply (vertex and face elements) or TressFX's .tfxmesh (the
// text mesh exported beside a .tfx); any other is an input error naming these.
Mesh loadMesh(const std::string& path);

// Same, from memory (used by the fuzz targets and tests).
Mesh parsePlyMesh(const uint8_t* data, std::size_t size, const std::string& name);
Mesh parseTfxMesh(const uint8_t* data, std::size_t size, const std::string& name);

}  // namespace sb
