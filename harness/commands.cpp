#include "harness/commands.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "backends/device.h"
#include "harness/image.h"
#include "harness/metrics.h"
#include "harness/render.h"
#include "scenes/options.h"
#include "scenes/scene.h"
#include "techniques/common/technique.h"

namespace sb {
namespace {

namespace fs = std::filesystem;

int gStatus = 0;

void printOptions(const std::vector<OptionInfo>& options) {
  for (const auto& o : options)
    std::cout << "      " << o.name << "=" << o.defaultValue << "  " << o.help << "\n";
}

void registerList(CLI::App& app) {
  auto* cmd = app.add_subcommand("list", "list scenes, techniques, their options and defaults");
  auto json = std::make_shared<bool>(false);
  cmd->add_flag("--json", *json, "print as JSON");
  cmd->callback([json] {
    runGuarded("list", [&] {
      if (*json) {
        nlohmann::json j;
        auto opts = [](const std::vector<OptionInfo>& v) {
          nlohmann::json a = nlohmann::json::array();
          for (const auto& o : v)
            a.push_back({{"name", o.name}, {"default", o.defaultValue}, {"help", o.help}});
          return a;
        };
        for (const auto& s : sceneCatalog())
          j["scenes"].push_back({{"name", s.name}, {"help", s.help}, {"options", opts(s.options)}});
        for (const auto& t : shadowCatalog())
          j["shadow"].push_back({{"name", t.name}, {"help", t.help}, {"options", opts(t.options)}});
        for (const auto& t : oitCatalog())
          j["oit"].push_back({{"name", t.name}, {"help", t.help}, {"options", opts(t.options)}});
        j["backends"] = {{{"name", "gl"}, {"platforms", {"egl", "osmesa"}}},
                         {{"name", "vulkan"}, {"platforms", {"headless"}}}};
        j["primitives"] = {"lines", "ribbons"};
        std::cout << j.dump(2) << "\n";
        return 0;
      }
      std::cout << "scenes (--scene NAME:key=value,...):\n";
      for (const auto& s : sceneCatalog()) {
        std::cout << "  " << s.name << "  " << s.help << "\n";
        printOptions(s.options);
      }
      std::cout << "shadow techniques (--shadow NAME:key=value,...):\n";
      for (const auto& t : shadowCatalog()) {
        std::cout << "  " << t.name << "  " << t.help << "\n";
        printOptions(t.options);
      }
      std::cout << "transparency techniques (--oit NAME:key=value,...):\n";
      for (const auto& t : oitCatalog()) {
        std::cout << "  " << t.name << "  " << t.help << "\n";
        printOptions(t.options);
      }
      std::cout << "backends (--backend): gl (--platform egl|osmesa), vulkan (headless)\n"
                << "primitives (--primitive): lines, ribbons (--ribbon-width PIXELS)\n";
      return 0;
    });
  });
}

// "gl" or "vulkan", and a platform of that backend; the closest valid name otherwise.
void checkBackendNames(const RenderRequest& req) {
  const std::vector<std::string> backends = {"gl", "vulkan"};
  if (std::find(backends.begin(), backends.end(), req.backend) == backends.end())
    throw InputError("--backend " + req.backend + ": " +
                     unknownNameMessage("backend", req.backend, backends));
  if (req.platform.empty()) return;
  const std::vector<std::string> platforms = req.backend == "gl"
                                                 ? std::vector<std::string>{"egl", "osmesa"}
                                                 : std::vector<std::string>{"headless"};
  if (std::find(platforms.begin(), platforms.end(), req.platform) == platforms.end())
    throw InputError("--platform " + req.platform + ": " +
                     unknownNameMessage(req.backend + " platform", req.platform, platforms));
}

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

// Options a command does not know, and stray arguments: CLI11 would only say
// "The following arguments were not expected"; this names the command and the
// closest valid option. Runs as soon as the command's arguments are parsed.
void rejectUnknownArguments(const CLI::App& cmd) {
  const std::vector<std::string> extra = cmd.remaining();
  if (extra.empty()) return;
  const std::string& arg = extra.front();
  if (arg.size() < 2 || arg[0] != '-')
    throw CLI::ParseError(cmd.get_name() + ": unexpected argument '" + arg + "'",
                          CLI::ExitCodes::ExtrasError);
  std::vector<std::string> valid;
  for (const CLI::Option* o : cmd.get_options()) {
    for (const auto& n : o->get_lnames()) valid.push_back("--" + n);
    for (const auto& n : o->get_snames()) valid.push_back("-" + n);
  }
  throw CLI::ParseError(
      unknownNameMessage(cmd.get_name() + " option", arg.substr(0, arg.find('=')), valid),
      CLI::ExitCodes::ExtrasError);
}

void registerRender(CLI::App& app) {
  auto* cmd = app.add_subcommand("render", "render one scene with one technique on one backend");
  auto req = std::make_shared<RenderRequest>();
  auto size = std::make_shared<std::string>("512x512");
  auto out = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto referenceOut = std::make_shared<std::string>();
  auto heatmap = std::make_shared<std::string>();
  auto view = std::make_shared<std::map<std::string, std::string>>();
  cmd->add_option("--scene", req->scene, "scene spec, e.g. curly:strands=20000,points=32,seed=7")
      ->capture_default_str();
  cmd->add_option("--shadow", req->shadow, "shadow technique spec, e.g. shadowmap:size=1024")
      ->capture_default_str();
  cmd->add_option("--oit", req->oit, "transparency technique spec, e.g. peel, abuffer")
      ->capture_default_str();
  cmd->add_flag("--reference", req->reference,
                "also render the reference (exact shadows + depth peeling) and report the error");
  cmd->add_flag(
      "--no-image", [req](std::int64_t) { req->image = false; },
      "with --reference: measure only the visibility error (no final shading pass)");
  cmd->add_option("--reference-out", *referenceOut, "with --reference: write the reference image");
  cmd->add_option("--heatmap", *heatmap,
                  "with --reference: write a heatmap of |image - reference| (full scale 0.25)");
  cmd->add_option("--backend", req->backend, "gl | vulkan")->capture_default_str();
  cmd->add_option("--platform", req->platform, "gl: egl (default) | osmesa; vulkan: headless");
  cmd->add_option("--size", *size, "image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--primitive", req->primitive, "lines | ribbons")->capture_default_str();
  cmd->add_option("--ribbon-width", req->ribbonWidth, "ribbon width in pixels")
      ->capture_default_str();
  cmd->add_option("--repeat", req->repeat, "timed frames")->capture_default_str();
  cmd->add_option("--warmup", req->warmup, "untimed frames first")->capture_default_str();
  cmd->add_option("--out", *out, "image file (.png 8-bit, .exr float)");
  cmd->add_flag("--json", *json, "print the report as one JSON object on stdout");
  cmd->add_flag("--validation", req->validation, "Vulkan validation layers on (counts messages)");
  for (const char* name :
       {"camera-eye", "camera-target", "camera-up", "fov", "near", "far", "light", "light-position",
        "light-direction", "light-color", "light-intensity"})
    cmd->add_option(std::string("--") + name, (*view)[name],
                    "override (x,y,z for vectors; light: directional|point)");
  cmd->callback([=] {
    runGuarded("render", [&] {
      auto [w, h] = parseSize(*size);
      req->width = w;
      req->height = h;
      checkBackendNames(*req);
      if (!out->empty()) checkOutputPath("--out", *out, {".png", ".exr"});
      if (!req->image && (!out->empty() || !referenceOut->empty() || !heatmap->empty()))
        throw InputError("--no-image writes no images: drop --out, --reference-out and --heatmap");
      for (const auto& [option, extra] : {std::pair{"--reference-out", referenceOut.get()},
                                          std::pair{"--heatmap", heatmap.get()}}) {
        if (extra->empty()) continue;
        if (!req->reference) throw InputError("--reference-out and --heatmap need --reference");
        checkOutputPath(option, *extra, {".png", ".exr"});
      }
      auto get = [&](const char* k) -> const std::string& { return (*view)[k]; };
      ViewOverrides& v = req->view;
      auto num = [&](const char* k) -> std::optional<float> {
        if (get(k).empty()) return std::nullopt;
        try {
          std::size_t used = 0;
          const float x = std::stof(get(k), &used);
          if (used == get(k).size() && std::isfinite(x)) return x;
        } catch (const std::exception&) {
        }
        throw InputError(std::string("--") + k + " " + get(k) + ": not a finite number");
      };
      auto vec = [&](const char* k) -> std::optional<glm::vec3> {
        if (get(k).empty()) return std::nullopt;
        return parseVec3(get(k), std::string("--") + k);
      };
      v.cameraEye = vec("camera-eye");
      v.cameraTarget = vec("camera-target");
      v.cameraUp = vec("camera-up");
      v.fov = num("fov");
      v.nearPlane = num("near");
      v.farPlane = num("far");
      if (!get("light").empty()) v.lightType = get("light");
      v.lightPosition = vec("light-position");
      v.lightDirection = vec("light-direction");
      v.lightColor = vec("light-color");
      v.lightIntensity = num("light-intensity");
      const RenderOutcome result = runRender(*req);
      if (!out->empty()) writeImage(result.image, *out);
      if (!referenceOut->empty()) writeImage(result.reference, *referenceOut);
      if (!heatmap->empty())
        writeImage(diffHeatmap(result.image, result.reference, 0.25), *heatmap);
      nlohmann::json report = result.report;
      if (!out->empty()) report["image"] = *out;
      if (*json) {
        std::cout << report.dump(2) << "\n";
      } else {
        std::cout << req->scene << " | shadow " << req->shadow << " | oit " << req->oit << " | "
                  << report["backend"].get<std::string>() << "/"
                  << report["platform"].get<std::string>() << " ("
                  << report["device"].get<std::string>() << ") | "
                  << report["scene"]["segments"].get<std::size_t>() << " segments | "
                  << req->primitive << " | " << *size << "\n";
        for (const auto& p : report["passes"])
          std::cout << "  " << p["name"].get<std::string>() << ": median "
                    << p["ms"]["median"].get<double>() << " ms (min "
                    << p["ms"]["min"].get<double>() << ", max " << p["ms"]["max"].get<double>()
                    << ", " << req->repeat << " runs)\n";
        std::cout << "  frame: median " << report["frame_ms"]["median"].get<double>() << " ms\n";
        if (report.contains("error"))
          std::cout << "  error against " << report["reference"]["shadow"].get<std::string>()
                    << " + " << report["reference"]["oit"].get<std::string>() << ": image "
                    << report["error"]["image"].dump() << ", visibility "
                    << report["error"]["visibility"].dump() << "\n";
        if (report.contains("depth_complexity"))
          std::cout << "  depth complexity: " << report["depth_complexity"].dump() << "\n";
        for (const auto& warning : report["warnings"])
          std::cout << "  warning: " << warning.get<std::string>() << "\n";
        if (!out->empty()) std::cout << "  wrote " << *out << "\n";
      }
      return 0;
    });
  });
}

void registerCompare(CLI::App& app) {
  auto* cmd = app.add_subcommand("compare", "image error between two files (RMSE, PSNR, max abs)");
  auto a = std::make_shared<std::string>();
  auto b = std::make_shared<std::string>();
  cmd->add_option("A", *a, "first image")->required();
  cmd->add_option("B", *b, "second image")->required();
  auto heatmap = std::make_shared<std::string>();
  auto scale = std::make_shared<double>(0.25);
  cmd->add_option("--heatmap", *heatmap, "write a viridis heatmap of |A - B| (PNG or EXR)");
  cmd->add_option("--heatmap-scale", *scale, "difference shown as the top colour")
      ->capture_default_str();
  cmd->callback([=] {
    runGuarded("compare", [&] {
      if (!heatmap->empty()) {
        if (!(*scale > 0)) throw InputError("--heatmap-scale must be positive");
        checkOutputPath("--heatmap", *heatmap, {".png", ".exr"});
      }
      const int status = runCompareCommand(*a, *b, std::cout, std::cerr);
      if (status == 0 && !heatmap->empty())
        writeImage(diffHeatmap(readImage(*a), readImage(*b), *scale), *heatmap);
      return status;
    });
  });
}

}  // namespace

void registerCommands(CLI::App& app) {
  registerList(app);
  registerRender(app);
  registerCompare(app);
  registerCheckCommands(app);
  registerProbeCommand(app);
  registerBenchCommand(app);
  registerSweepCommands(app);
  registerCompareRunsCommand(app);
  // Unknown options get the closest valid one, for every command.
  for (CLI::App* cmd : app.get_subcommands([](CLI::App*) { return true; }))
    cmd->parse_complete_callback([cmd] { rejectUnknownArguments(*cmd); });
}

int lastCommandStatus() { return gStatus; }

void runGuarded(const char* command, const std::function<int()>& body) {
  try {
    gStatus = body();
  } catch (const InputError& e) {
    std::cerr << "strandbench " << command << ": " << e.what() << "\n";
    gStatus = 2;
  } catch (const DeviceError& e) {
    std::cerr << "strandbench " << command << ": " << e.what() << "\n";
    gStatus = 2;
  }
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

void checkRenderRequest(const RenderRequest& req, bool device, RenderCache* cache) {
  if (req.repeat < 1) throw InputError("--repeat must be at least 1");
  if (req.warmup < 0) throw InputError("--warmup must be at least 0");
  checkBackendNames(req);
  std::shared_ptr<const Scene> scene;
  if (cache && cache->scenes.count(req.scene)) scene = cache->scenes.at(req.scene);
  if (!scene) {
    scene = std::make_shared<const Scene>(makeScene(Spec::parse(req.scene)));
    if (cache) cache->scenes[req.scene] = scene;
  }
  makeShadowTechnique(Spec::parse(req.shadow));
  makeOitTechnique(Spec::parse(req.oit));
  makeRenderSettings(req, *scene);
  if (device) makeRequestDevice(req);
}

}  // namespace sb
