// Scene data helpers, spec parsing and file reading shared by the loaders.
#include "scenes/scene.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <string_view>

#include "scenes/loader_util.h"
#include "scenes/mesh_loaders.h"

namespace sb {

std::size_t Strands::segmentCount() const {
  std::size_t n = 0;
  for (uint32_t c : pointCount) n += c > 0 ? c - 1 : 0;
  return n;
}

float Bounds::radius() const { return 0.5f * glm::length(max - min); }

Bounds Scene::bounds() const {
  constexpr float inf = std::numeric_limits<float>::infinity();
  glm::vec3 lo(inf), hi(-inf);
  auto add = [&](const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  };
  for (const glm::vec3& p : strands.points) add(p);
  for (const glm::vec3& p : mesh.positions) add(p);
  Bounds b;
  if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) {
    // Empty scene: a unit cube around the origin, so cameras and lights stay finite.
    b.min = glm::vec3(-0.5f);
    b.max = glm::vec3(0.5f);
    return b;
  }
  b.min = lo;
  b.max = hi;
  return b;
}

namespace detail {

void fail(const std::string& name, const std::string& what) {
  throw InputError(name + ": " + what);
}

std::vector<uint8_t> readFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError("cannot open '" + path + "': " + std::strerror(errno));
  }
  in.seekg(0, std::ios::end);
  const std::streamoff end = in.tellg();
  if (end < 0) throw InputError("cannot read '" + path + "': not a regular file");
  in.seekg(0, std::ios::beg);
  std::vector<uint8_t> bytes(static_cast<std::size_t>(end));
  if (!bytes.empty() &&
      !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()))) {
    throw InputError("cannot read '" + path + "': read failed");
  }
  // A repository's large file not fetched: its place holds git-lfs's pointer
  // ("version https://git-lfs.github.com/spec/v1", "oid sha256:...", "size N"),
  // which every loader would call short or malformed.
  static constexpr std::string_view kLfs = "version https://git-lfs.github.com/spec/";
  if (bytes.size() >= kLfs.size() && std::equal(kLfs.begin(), kLfs.end(), bytes.begin())) {
    const std::string text(bytes.begin(), bytes.end());
    std::string size;  // the real file's, when the pointer says
    if (const std::size_t at = text.find("\nsize "); at != std::string::npos) {
      const std::size_t digits = text.find_first_not_of("0123456789", at + 6);
      if (digits > at + 6) size = " (of " + text.substr(at + 6, digits - (at + 6)) + " bytes)";
    }
    throw InputError(path + ": an unfetched git-lfs pointer, not the file itself" + size +
                     ": run `git lfs pull` in its repository to fetch it (git-lfs must be "
                     "installed)");
  }
  return bytes;
}

void setNormals(Mesh& m, const std::vector<glm::vec3>& given) {
  const std::size_t n = m.positions.size();
  // Area-weighted normals (the cross product's length is twice the triangle area).
  std::vector<glm::vec3> computed(n, glm::vec3(0.0f));
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const uint32_t a = m.indices[t], b = m.indices[t + 1], c = m.indices[t + 2];
    const glm::vec3 cross =
        glm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
    computed[a] += cross;
    computed[b] += cross;
    computed[c] += cross;
  }
  m.normals.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    glm::vec3 v = given.empty() ? computed[i] : given[i];
    if (!(glm::dot(v, v) > 1e-30f)) v = computed[i];
    const float len2 = glm::dot(v, v);
    m.normals[i] = len2 > 1e-30f && std::isfinite(len2) ? v / std::sqrt(len2) : glm::vec3(0, 1, 0);
  }
}

}  // namespace detail

Strands loadHair(const std::string& path) {
  const std::vector<uint8_t> bytes = detail::readFileBytes(path);
  return parseHair(bytes.data(), bytes.size(), path);
}

Strands loadTfx(const std::string& path, std::vector<std::string>* warnings) {
  const std::vector<uint8_t> bytes = detail::readFileBytes(path);
  return parseTfx(bytes.data(), bytes.size(), path, warnings);
}

Strands loadPly(const std::string& path, uint32_t pointsPerStrand) {
  const std::vector<uint8_t> bytes = detail::readFileBytes(path);
  return parsePly(bytes.data(), bytes.size(), path, pointsPerStrand);
}

namespace {

// ".ply" for "a/b.PLY"; "" without one.
std::string lowerExtension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  std::string ext;
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) {
    ext = path.substr(dot);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return ext;
}

}  // namespace

Mesh loadMesh(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".obj") return loadObj(path);
  if (ext != ".ply" && ext != ".tfxmesh")
    throw InputError(
        path + ": mesh= takes OBJ (.obj), PLY (.ply) and TressFX (.tfxmesh) meshes, " +
        (ext.empty() ? std::string("not a file without an extension") : "not '" + ext + "'"));
  const std::vector<uint8_t> bytes = detail::readFileBytes(path);
  return ext == ".ply" ? parsePlyMesh(bytes.data(), bytes.size(), path)
                       : parseTfxMesh(bytes.data(), bytes.size(), path);
}

Strands loadStrandFile(const std::string& path, uint32_t pointsPerStrand,
                       std::vector<std::string>* warnings) {
  const std::string ext = lowerExtension(path);
  if (ext == ".ply") return loadPly(path, pointsPerStrand);
  if (pointsPerStrand != 0 && (ext == ".hair" || ext == ".tfx")) {
    throw InputError(path + ": points_per_strand= applies to .ply files only (a " + ext +
                     " file says where its strands end)");
  }
  if (ext == ".hair") return loadHair(path);
  if (ext == ".tfx") return loadTfx(path, warnings);
  throw InputError(path + ": unknown strand file extension '" + ext +
                   "' (expected .hair, .tfx or .ply)");
}

Scene withLevelOfDetail(const Scene& full, const Camera& camera, uint32_t imageHeight) {
  Scene s;  // all but the strands, which the rule makes again
  s.name = full.name;
  s.mesh = full.mesh;
  s.hairAlpha = full.hairAlpha;
  s.shadowAlpha = full.shadowAlpha;
  s.hairColor = full.hairColor;
  s.frameByBox = full.frameByBox;
  s.warnings = full.warnings;
  s.up = full.up;
  s.upReason = full.upReason;
  s.groom = full.groom;
  groomLevelOfDetail(s.groom, camera, imageHeight);
  s.strands = generateStrands(s.groom);
  s.strands.thicknessFallback = full.strands.thicknessFallback;
  return s;
}

}  // namespace sb
