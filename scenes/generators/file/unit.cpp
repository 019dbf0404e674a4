// Strands from a file (.hair, .tfx, .ply), optionally with a mesh: turned to y up, thinned
// to strands= and recoloured where asked.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>

#include "scenes/mesh_loaders.h"
#include "scenes/scene_unit.h"

namespace sb {
namespace {

struct FileOptions : SceneBase {
  std::string path, up, color;
  int64_t keep = 0;              // strands=; 0: all
  uint32_t pointsPerStrand = 0;  // 0 = not given
};
using FO = FileOptions;

// "R/G/B", each in [0,1] (a spec's commas separate its options); "file": none.
std::optional<glm::vec3> colorOption(const FileOptions& o) {
  const std::string& t = o.color;
  if (t == "file") return std::nullopt;
  float c[3];
  std::size_t at = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t end = i < 2 ? t.find('/', at) : t.size();
    char* stop = nullptr;
    const std::string part = end == std::string::npos ? "" : t.substr(at, end - at);
    c[i] = std::strtof(part.c_str(), &stop);
    if (part.empty() || *stop != '\0' || !(c[i] >= 0.0f && c[i] <= 1.0f))
      throw o.error("color=" + t + ": expected file or R/G/B, three numbers in [0,1]");
    at = end + 1;
  }
  return glm::vec3(c[0], c[1], c[2]);
}

// up=auto for a format that does not say which way is up (PLY): the axis among y, z, -y
// and -z along which the strands' roots lie above their tips (hanging hair), when it is
// clear: the roots-to-tips offsets along it sum to at least kClearlyHanging of their
// lengths. Else y. Sets `why`.
constexpr double kClearlyHanging = 0.3;

std::string upFromRootsAndTips(const Strands& s, std::string& why) {
  glm::dvec3 sum(0.0);
  double length = 0;
  for (std::size_t i = 0; i < s.strandCount(); ++i) {
    if (s.pointCount[i] < 2) continue;
    const glm::dvec3 d = glm::dvec3(s.points[s.firstPoint[i]]) -
                         glm::dvec3(s.points[s.firstPoint[i] + s.pointCount[i] - 1]);
    sum += d;
    length += glm::length(d);
  }
  const std::pair<const char*, double> axes[] = {
      {"y", sum.y}, {"-y", -sum.y}, {"z", sum.z}, {"-z", -sum.z}};
  const auto* best = &axes[0];
  for (const auto& a : axes)
    if (a.second > best->second) best = &a;
  const double share = length > 0 ? best->second / length : 0.0;
  char pct[16];
  std::snprintf(pct, sizeof pct, "%.0f%%", 100.0 * std::max(share, 0.0));
  if (share < kClearlyHanging) {
    why = std::string(
              "auto: the format does not say, and roots and tips give no clear "
              "direction (the most, along ") +
          best->first + ", is " + pct + " of the strands' root-to-tip lengths): y";
    return "y";
  }
  why = std::string("auto: the format does not say; the roots lie above the tips along ") +
        best->first + " (" + pct + " of the strands' root-to-tip lengths), as hanging hair's";
  return best->first;
}

Scene makeFile(const FileOptions& o) {
  Scene scene;
  const std::string& path = o.path;
  if (path.empty()) throw o.error("path= is required (a .hair, .tfx or .ply strand file)");
  const int64_t keep = o.keep;                         // 0 = all
  const uint32_t pointsPerStrand = o.pointsPerStrand;  // 0 = not given
  std::string up = o.up;
  const std::optional<glm::vec3> color = colorOption(o);
  scene.frameByBox = true;
  const std::string& mesh = o.mesh;
  if (!mesh.empty()) scene.mesh = loadMesh(mesh);
  Strands all = loadStrandFile(path, pointsPerStrand, &scene.warnings);
  const auto extension = [&](const char* e) {
    const std::size_t n = std::strlen(e);
    return path.size() > n && path.compare(path.size() - n, n, e) == 0;
  };
  if (up != "auto") {
    scene.upReason = "up=" + up + " asked for";
  } else if (extension(".hair")) {
    up = "z";
    scene.upReason = "auto: the HAIR format's models (Yuksel's) are z-up";
  } else if (extension(".tfx")) {
    up = "y";
    scene.upReason = "auto: TressFX's models are y-up";
  } else {
    up = upFromRootsAndTips(all, scene.upReason);
  }
  scene.up = up;
  // The file's up axis turned to +y (a rotation about x, so handedness holds), the
  // strands and the mesh alike; its colours replaced where asked.
  const auto turn = [&](glm::vec3 p) {
    if (up == "z") return glm::vec3(p.x, p.z, -p.y);
    if (up == "-z") return glm::vec3(p.x, -p.z, p.y);
    if (up == "-y") return glm::vec3(p.x, -p.y, -p.z);
    return p;
  };
  if (up != "y") {
    for (glm::vec3& p : all.points) p = turn(p);
    for (glm::vec3& p : scene.mesh.positions) p = turn(p);
    for (glm::vec3& n : scene.mesh.normals) n = turn(n);
  }
  if (color)
    for (glm::vec3& c : all.colors) c = *color;
  if (keep == 0 || uint64_t(keep) == all.strandCount()) {
    scene.strands = std::move(all);
    return scene;
  }
  if (uint64_t(keep) > all.strandCount()) {
    throw o.error("strands=" + std::to_string(keep) + " exceeds the " +
                  std::to_string(all.strandCount()) + " strands in " + path);
  }
  Strands& out = scene.strands;
  out.thicknessFallback = all.thicknessFallback;
  const uint64_t total = all.strandCount();
  for (uint64_t i = 0; i < uint64_t(keep); ++i) {
    const std::size_t s = std::size_t(i * total / uint64_t(keep));
    const uint32_t first = all.firstPoint[s], count = all.pointCount[s];
    out.firstPoint.push_back(uint32_t(out.points.size()));
    out.pointCount.push_back(count);
    out.points.insert(out.points.end(), all.points.begin() + first,
                      all.points.begin() + first + count);
    out.colors.insert(out.colors.end(), all.colors.begin() + first,
                      all.colors.begin() + first + count);
    out.thickness.insert(out.thickness.end(), all.thickness.begin() + first,
                         all.thickness.begin() + first + count);
    out.transparency.insert(out.transparency.end(), all.transparency.begin() + first,
                            all.transparency.begin() + first + count);
  }
  return scene;
}

}  // namespace
}  // namespace sb

SB_SCENE(sceneUnit<FO>(
    "file", "strands from a file (.hair, .tfx, .ply), optionally with a mesh", 7,
    {opt::text(&FO::path, "path", "", "strand file (required): .hair, .tfx or .ply"),
     opt::inherited<FO>(opt::text(&SceneBase::mesh, "mesh", "",
                                  "mesh file drawn opaque (.obj, .ply, .tfxmesh)")),
     {{opt::text("strands", "all", "keep this many strands, evenly spaced (default: all)"),
       [](FO& s, const OptionReader& r) {
         s.keep = r.text("strands") == "all" ? 0 : r.integer("strands", 1, kMaxStrands);
       },
       [](const FO& s) { return s.keep ? std::to_string(s.keep) : "all"; }}},
     scene_opt::optional<FO>(
         "points_per_strand",
         "PLY without a 'strand' element (e.g. NeuralHaircut): strands of N consecutive "
         "vertices, 2.." +
             std::to_string(kMaxPointsPerStrand),
         [](FO& s, const OptionReader& r) {
           if (r.has("points_per_strand"))
             s.pointsPerStrand = uint32_t(r.integer("points_per_strand", 2, kMaxPointsPerStrand));
         },
         [](const FO& s) { return s.pointsPerStrand ? std::to_string(s.pointsPerStrand) : ""; }),
     opt::inherited<FO>(alphaOptions()),
     opt::inherited<FO>(seedOption("seed of the generation rule (guides=, instances=)")),
     opt::choice(&FO::up, "up", "auto", {"auto", "y", "z", "-y", "-z"},
                 "the file's up axis, turned to +y: auto (z for .hair, Yuksel's models are "
                 "z-up; y for .tfx, TressFX's; for .ply, which does not say, the axis "
                 "along which the roots lie above the tips, as hanging hair's do, else "
                 "y), y, z, -y or -z; the render JSON's scene.up and up_reason"),
     opt::text(&FO::color, "color", "file",
               "strand colours: file (the file's own, where it has them) or R/G/B in "
               "[0,1] for every strand (color=0.45/0.3/0.18)")},
    makeFile));
