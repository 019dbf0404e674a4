#include "harness/checks.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "base/errors.h"
#include "base/options.h"
#include "harness/render.h"
#include "harness/technique_list.h"
#include "scenes/scene.h"
#include "render/common/unit.h"
#include "render/generation/generation.h"

namespace sb {
namespace {

namespace fs = std::filesystem;

// Creates and removes a file in `dir`: unlike permission bits, this also holds
// for root (read-only mounts, /proc, /sys).
bool folderWritable(const fs::path& dir) {
  const fs::path probe = dir / (".strandbench-write-test-" + std::to_string(::getpid()));
  FILE* f = std::fopen(probe.c_str(), "wb");
  if (!f) return false;
  std::fclose(f);
  std::error_code ec;
  fs::remove(probe, ec);
  return true;
}

}  // namespace

std::string shellQuoted(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                        "0123456789-_.,:=/+") == std::string::npos)
    return s;
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

void checkOutputPath(const std::string& option, const std::string& path,
                     const std::vector<std::string>& extensions) {
  const std::string what = option + " " + path + ": ";
  const std::string ext = fs::path(path).extension().string();
  if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) {
    std::string list;
    for (std::size_t i = 0; i < extensions.size(); ++i)
      list += (i == 0 ? "" : i + 1 == extensions.size() ? " or " : ", ") + extensions[i];
    throw InputError(what + "the file must end in " + list);
  }
  const fs::path target = fs::absolute(path);
  const fs::path dir = target.parent_path();
  std::error_code ec;
  if (!fs::exists(dir, ec)) throw InputError(what + "folder " + dir.string() + " does not exist");
  if (!fs::is_directory(dir, ec))
    throw InputError(what + dir.string() + " is a file, not a folder");
  if (fs::is_directory(target, ec)) throw InputError(what + "it is a folder, not a file");
  if (!folderWritable(dir)) throw InputError(what + "folder " + dir.string() + " is not writable");
}

void checkOutputFolder(const std::string& option, const std::string& path) {
  const std::string what = option + " " + path + ": ";
  fs::path existing = fs::absolute(path).lexically_normal();
  std::error_code ec;
  while (!fs::exists(existing, ec) && existing.has_parent_path() &&
         existing != existing.parent_path())
    existing = existing.parent_path();
  if (!fs::is_directory(existing, ec))
    throw InputError(what + existing.string() + " is a file, not a folder");
  if (!folderWritable(existing))
    throw InputError(what + "folder " + existing.string() + " is not writable");
}

namespace {
// Why --geometry mesh cannot run this request before any device is made (the
// backend, the techniques' capabilities), or "". A Vulkan device without
// VK_EXT_mesh_shader is refused once it is made (render.cpp, openDevice).
std::string meshPathRefusal(const RenderRequest& req) {
  if (req.backend != "vulkan")
    return "mesh shaders run on Vulkan only (VK_EXT_mesh_shader), not on --backend " + req.backend +
           "; use --backend vulkan (Mesa 25.0's lavapipe has them: --driver "
           "mesa-25.0)";
  const auto refusing = [](const TechniqueDescriptor& d) { return !d.caps.meshRefusal.empty(); };
  for (const auto& [family, spec] :
       {std::pair{Family::Shadow, req.shadow}, std::pair{Family::Transparency, req.oit}}) {
    const TechniqueDescriptor& d = findTechnique(family, Spec::parse(spec).name);
    if (!refusing(d)) continue;
    std::string names;
    for (const std::string& n : techniqueNames(family, refusing))
      names += (names.empty() ? "" : ", ") + n;
    return std::string(familyName(family)) + " technique '" + d.name +
           "' does not run on it: " + d.caps.meshRefusal +
           ", and the mesh path makes the strands only inside the strand draw (not on the mesh "
           "path: " +
           names + "; use --geometry compute)";
  }
  return "";
}
}  // namespace

void checkRenderRequest(const RenderRequest& req, bool device, RenderCache* cache,
                        Spelling spelling) {
  checkRequest(req, spelling);
  // Names and options of the specs, each message led by the setting it is in.
  auto named = [&](const char* key, const std::string& value, const auto& check) {
    try {
      check();
    } catch (const InputError& e) {
      throw InputError(settingMessage(*findSetting(key), spelling, value, e.what()));
    }
  };
  std::shared_ptr<const Scene> scene;
  if (cache && cache->scenes.count(req.scene)) scene = cache->scenes.at(req.scene);
  if (!scene) {
    named("scene", req.scene,
          [&] { scene = std::make_shared<const Scene>(makeScene(Spec::parse(req.scene))); });
    if (cache) cache->scenes[req.scene] = scene;
  }
  checkTechniqueSpecs(req, spelling);
  // --geometry: refused up front where the path cannot make this scene's strands.
  if (const std::string why = geometryRefusal(req.geometry, *scene); !why.empty())
    throw InputError(settingMessage(*findSetting("geometry"), spelling, req.geometry, why));
  if (req.geometry == "mesh")
    if (const std::string why = meshPathRefusal(req); !why.empty())
      throw InputError(settingMessage(*findSetting("geometry"), spelling, req.geometry, why));
  makeRenderSettings(req, *scene);
  if (device) makeRequestDevice(req);
}

}  // namespace sb
