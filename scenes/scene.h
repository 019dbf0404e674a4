// CPU-side scene data: strands (hair, fur) and an optional opaque mesh, plus the
// camera and light fitted to them. Produced by generators and file loaders,
// consumed by the renderer (which uploads it through the Device).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/errors.h"   // InputError
#include "base/options.h"  // Spec, OptionInfo
#include "scenes/groom.h"

namespace sb {

struct Strands {
  // Strand s owns points [firstPoint[s], firstPoint[s] + pointCount[s]).
  std::vector<uint32_t> firstPoint;
  std::vector<uint32_t> pointCount;
  std::vector<glm::vec3> points;
  std::vector<glm::vec3> colors;    // per point, linear RGB
  std::vector<float> thickness;     // per point, world units
  std::vector<float> transparency;  // per point (HAIR semantics: 0 = opaque)
  // The file gave no thickness (TressFX, PLY): `thickness` holds the loaders' fallback
  // (detail::kDefaultThickness world units), not a width of the strands; the render JSON's
  // scene.thickness_source says "fallback", and the path reference's world width takes
  // its own (harness/references/pbr/pbr_reference.cpp).
  bool thicknessFallback = false;

  std::size_t strandCount() const { return pointCount.size(); }
  std::size_t segmentCount() const;  // sum over strands of max(pointCount-1, 0)
};

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // per position; computed (area-weighted) when absent
  std::vector<uint32_t> indices;   // triangles
  std::size_t triangleCount() const { return indices.size() / 3; }
};

struct Bounds {
  glm::vec3 min{0.0f}, max{0.0f};
  glm::vec3 center() const { return 0.5f * (min + max); }
  float radius() const;  // half the diagonal
};

struct Scene {
  std::string name;  // the spec it came from
  Strands strands;
  Mesh mesh;                 // may be empty
  float hairAlpha = 1.0f;    // hair opacity for transparency (scene option alpha=)
  float shadowAlpha = 0.5f;  // per-fragment shadow opacity alpha_s (shadow_alpha=)
  glm::vec3 hairColor{0.45f, 0.3f, 0.18f};
  // The default camera fits the bounding box seen from +z (files: elongated models fill
  // the frame), else the bounding sphere (the generated scenes and their baselines).
  bool frameByBox = false;
  // Input accepted with a defect worth knowing (e.g. a file cut inside a block that is
  // not read); `render` reports them under "warnings".
  std::vector<std::string> warnings;
  // Files: the up axis the file was turned from ("y", "z", "-y", "-z") and why
  // ("up=z asked for", "auto: ..."); empty for generated scenes (y up by construction).
  std::string up, upReason;
  // Made with guides= or instances=: the guides and rule `strands` were made from
  // on the CPU (render --geometry compute makes them again on the GPU); else empty.
  Groom groom;
  Bounds bounds() const;  // strands and mesh together
};

// The registered scene generators (scenes/scene_unit.h), in their order.
struct SceneInfo {
  std::string name;
  std::string help;
  std::vector<OptionInfo> options;
  std::string folder;  // scenes/generators/<folder>/
};
const std::vector<SceneInfo>& sceneCatalog();

// Builds a scene from a spec such as "curly:strands=20000,points=32,seed=7" or
// "file:path=../shared/models/straight.hair". Unknown scene or option names,
// out-of-range values and bad files throw InputError.
Scene makeScene(const Spec& spec);

// The scene as a view draws it: a scene whose groom has a level of detail
// (lod=, lod_pixels=; Groom::hasLod) made again with the strands
// groomLevelOfDetail keeps for this camera and image height. makeScene makes
// the full model, which the camera is fitted to and the full model's reference draws.
struct Camera;
Scene withLevelOfDetail(const Scene& full, const Camera& camera, uint32_t imageHeight);

// Loaders (throw InputError naming the file and the problem). `warnings`, when given,
// receives what a loader accepted but the user should hear about ("<file>: <what>").
// pointsPerStrand (PLY only; 0 = not given): a PLY without a 'strand' element is read as
// strands of that many consecutive vertices (NeuralHaircut-style files).
Strands loadHair(const std::string& path);  // Cem Yuksel's HAIR
// AMD TressFX .tfx: binary versions 3 and 4, and the text form of TressFX 1.x/2.x.
Strands loadTfx(const std::string& path, std::vector<std::string>* warnings = nullptr);
// PLY strands: vertex + strand(nsegs), or vertex only with pointsPerStrand.
Strands loadPly(const std::string& path, uint32_t pointsPerStrand = 0);
Mesh loadObj(const std::string& path);  // triangulated OBJ
// By extension; pointsPerStrand is an input error for anything but .ply.
Strands loadStrandFile(const std::string& path, uint32_t pointsPerStrand = 0,
                       std::vector<std::string>* warnings = nullptr);

// Same, from memory (used by the fuzz targets and tests).
Strands parseHair(const uint8_t* data, std::size_t size, const std::string& name);
Strands parseTfx(const uint8_t* data, std::size_t size, const std::string& name,
                 std::vector<std::string>* warnings = nullptr);
Strands parsePly(const uint8_t* data, std::size_t size, const std::string& name,
                 uint32_t pointsPerStrand = 0);
Mesh parseObj(const std::string& text, const std::string& name);  // OBJ text

}  // namespace sb
