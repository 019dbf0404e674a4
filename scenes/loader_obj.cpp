// Triangulated OBJ meshes through tinyobjloader. Positions stay unsplit (one vertex per
// OBJ position), so vertex counts match the file; normals come from the file when every
// face corner has one (averaged per position), else are computed area-weighted.
#include <tiny_obj_loader.h>

#include <limits>

#include "scenes/loader_util.h"
#include "scenes/scene.h"

namespace sb {

Mesh parseObj(const std::string& text, const std::string& name) {
  using detail::fail;
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, "", config)) {
    std::string err = reader.Error();
    while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
    fail(name, "cannot parse OBJ" + (err.empty() ? std::string() : ": " + err));
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const std::size_t numPositions = attrib.vertices.size() / 3;
  if (numPositions == 0) fail(name, "OBJ has no vertices");
  if (numPositions > std::numeric_limits<uint32_t>::max()) fail(name, "OBJ has too many vertices");

  Mesh m;
  m.positions.resize(numPositions);
  for (std::size_t i = 0; i < numPositions; ++i) {
    m.positions[i] =
        glm::vec3(attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]);
    if (!detail::finite3(m.positions[i])) {
      fail(name, "vertex " + std::to_string(i + 1) + " has a NaN or infinite coordinate");
    }
  }
  const std::size_t numNormals = attrib.normals.size() / 3;
  std::vector<glm::vec3> fileNormals(numPositions, glm::vec3(0.0f));
  bool allCornersHaveNormals = numNormals > 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    std::size_t offset = 0;
    for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      const std::size_t fv = mesh.num_face_vertices[f];
      if (offset + fv > mesh.indices.size()) fail(name, "inconsistent face data");
      if (fv == 3) {
        for (std::size_t k = 0; k < 3; ++k) {
          const tinyobj::index_t& idx = mesh.indices[offset + k];
          if (idx.vertex_index < 0 || std::size_t(idx.vertex_index) >= numPositions) {
            fail(name, "face " + std::to_string(f + 1) + " of '" + shape.name +
                           "' refers to a vertex that does not exist");
          }
          m.indices.push_back(uint32_t(idx.vertex_index));
          if (idx.normal_index >= 0 && std::size_t(idx.normal_index) < numNormals) {
            const float* n = &attrib.normals[3 * std::size_t(idx.normal_index)];
            const glm::vec3 nv(n[0], n[1], n[2]);
            if (detail::finite3(nv)) fileNormals[std::size_t(idx.vertex_index)] += nv;
          } else {
            allCornersHaveNormals = false;
          }
        }
      }
      offset += fv;
    }
  }
  if (m.indices.empty()) fail(name, "OBJ has no faces");

  detail::setNormals(m, allCornersHaveNormals ? fileNormals : std::vector<glm::vec3>{});
  return m;
}

Mesh loadObj(const std::string& path) {
  const std::vector<uint8_t> bytes = detail::readFileBytes(path);
  return parseObj(std::string(bytes.begin(), bytes.end()), path);
}

}  // namespace sb
