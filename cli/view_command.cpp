// `strandbench view`: the scene in a window (`--platform window` of either
// backend), with the camera and light under the mouse, the techniques under
// the keyboard, a compare mode (technique | reference | error heatmap, the
// reference rendered on demand), and screenshots that carry the `render`
// command line and suite case reproducing them. `--script FILE` plays a
// timed list of actions through the same handlers, for demos and tests. The
// state (techniques, times, memory, PSNR) is drawn over the image in the
// window (cli/view_overlay.h, key O) and written in the title.
//
// Every frame is rendered by runRender on the window's device (so what is
// shown is exactly what `render` computes) and the image chosen by the mode
// is uploaded and presented. Input reaches this file only through the
// platform-neutral backends/window.h.
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <iostream>
#include <sstream>
#include <thread>

#include "backends/window.h"
#include "base/options.h"
#include "cli/commands.h"
#include "cli/view_overlay.h"
#include "harness/render.h"
#include "harness/settings.h"
#include "imaging/image.h"
#include "imaging/metrics.h"
#include "render/common/unit.h"
#include "reports/stats.h"

namespace sb {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// ---- the script: "MS ACTION ARGS..." per line, '#' comments ----

struct ScriptAction {
  double atMs = 0;
  std::string action;  // key | drag | scroll | resize | screenshot | quit
  std::vector<std::string> args;
  int line = 0;
};

const char* kScriptHelp =
    "script lines: MS ACTION ARGS (MS: milliseconds from the start, non-decreasing; '#' starts "
    "a comment). Actions: key NAME [shift] [ctrl] [alt]; drag left|right|middle DX DY [shift] "
    "[ctrl]; scroll STEPS; resize W H; screenshot NAME; quit";

// The keys Viewer::key acts on: a script's key is one of them (a typo would do nothing).
const std::vector<std::string> kScriptKeys = {"S", "T", "Up", "Down", "Right", "Left",   "C",
                                              "O", "R", "P",  "F12",  "H",     "Escape", "Q"};

std::vector<ScriptAction> parseScript(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("--script " + path + ": cannot read the file");
  std::vector<ScriptAction> actions;
  std::string text;
  int lineNo = 0;
  double last = 0;
  while (std::getline(in, text)) {
    ++lineNo;
    if (auto hash = text.find('#'); hash != std::string::npos) text.resize(hash);
    std::istringstream words(text);
    std::vector<std::string> w;
    for (std::string x; words >> x;) w.push_back(x);
    if (w.empty()) continue;
    const std::string where = "--script " + path + ":" + std::to_string(lineNo) + ": ";
    auto number = [&](const std::string& s, const char* what) {
      char* end = nullptr;
      const double v = std::strtod(s.c_str(), &end);
      if (s.empty() || *end != '\0' || !std::isfinite(v))
        throw InputError(where + what + " '" + s + "' is not a number (" + kScriptHelp + ")");
      return v;
    };
    ScriptAction a;
    a.line = lineNo;
    a.atMs = number(w[0], "time");
    if (a.atMs < last)
      throw InputError(where + "time " + w[0] + " is before the previous line's (" +
                       std::to_string(last) + "): times must not decrease");
    last = a.atMs;
    if (w.size() < 2) throw InputError(where + "no action (" + kScriptHelp + ")");
    a.action = w[1];
    a.args.assign(w.begin() + 2, w.end());
    const std::size_t n = a.args.size();
    auto modifiers = [&](std::size_t from) {
      for (std::size_t i = from; i < n; ++i)
        if (a.args[i] != "shift" && a.args[i] != "ctrl" && a.args[i] != "alt")
          throw InputError(where + "'" + a.args[i] + "' is not a modifier (shift, ctrl, alt)");
    };
    if (a.action == "key") {
      if (n < 1) throw InputError(where + "key needs a key name");
      if (std::find(kScriptKeys.begin(), kScriptKeys.end(), a.args[0]) == kScriptKeys.end())
        throw InputError(where + unknownNameMessage("key", a.args[0], kScriptKeys));
      modifiers(1);
    } else if (a.action == "drag") {
      if (n < 3 || (a.args[0] != "left" && a.args[0] != "right" && a.args[0] != "middle"))
        throw InputError(where + "drag needs left|right|middle DX DY");
      number(a.args[1], "DX");
      number(a.args[2], "DY");
      modifiers(3);
    } else if (a.action == "scroll") {
      if (n != 1) throw InputError(where + "scroll needs STEPS");
      number(a.args[0], "STEPS");
    } else if (a.action == "resize") {
      if (n != 2) throw InputError(where + "resize needs W H");
      for (const auto& s : a.args) {
        const double v = number(s, "size");
        if (v < 16 || v > 4096 || v != std::floor(v))
          throw InputError(where + "resize " + s + ": a whole number of pixels in 16..4096");
      }
    } else if (a.action == "screenshot") {
      if (n != 1 || a.args[0].find('/') != std::string::npos || a.args[0].empty())
        throw InputError(where + "screenshot needs a NAME (no '/': it goes to --screenshot-dir)");
    } else if (a.action == "quit") {
      if (n != 0) throw InputError(where + "quit takes nothing");
    } else {
      throw InputError(where + "unknown action '" + a.action + "' (" + kScriptHelp + ")");
    }
    actions.push_back(a);
  }
  return actions;
}

// ---- the main option of each technique, stepped with the arrow keys ----

// The next name in a family (wrapping), options dropped.
std::string cycle(Family family, const std::string& spec, int step) {
  const std::vector<const TechniqueDescriptor*> all = techniques(family);
  const std::string name = Spec::parse(spec).name;
  std::size_t i = 0;
  while (i < all.size() && all[i]->name != name) ++i;
  const long long n = static_cast<long long>(all.size());
  return all[static_cast<std::size_t>(((static_cast<long long>(i) + step) % n + n) % n)]->name;
}

// The spec with the option its descriptor names as stepped (the one that most
// changes cost and quality) stepped; unchanged when it has none.
std::string stepMain(Family family, const std::string& specText, int step) {
  Spec spec = Spec::parse(specText);
  const TechniqueDescriptor* t = tryFindTechnique(family, spec.name);
  if (!t || !t->stepped) return specText;
  const SteppedOption& m = *t->stepped;
  auto opt = std::find_if(t->options.begin(), t->options.end(),
                          [&](const OptionInfo& o) { return o.name == m.option; });
  if (opt == t->options.end()) return specText;
  const auto given = spec.options.find(m.option);
  long long v = std::stoll(given != spec.options.end() ? given->second : opt->defaultValue);
  v = m.doubling ? (step > 0 ? v * 2 : v / 2) : v + step;
  spec.options[m.option] = std::to_string(std::clamp(v, m.min, m.max));
  return spec.str();
}

// ---- the reproducing command line and suite case ----

// The settings that differ from a default request (scene, techniques and
// backend always): what the picture depends on. Headless (the platform is left
// to its default); timing and validation are the user's to add.
std::vector<std::pair<const Setting*, nlohmann::ordered_json>> caseSettings(
    const RenderRequest& r) {
  const RenderRequest defaults;
  std::vector<std::pair<const Setting*, nlohmann::ordered_json>> out;
  for (const Setting& s : settingsTable()) {
    if (s.key == "platform" || s.key == "repeat" || s.key == "warmup" || s.key == "validation")
      continue;
    const auto v = s.get(r);
    const bool always =
        s.key == "scene" || s.key == "shadow" || s.key == "oit" || s.key == "backend";
    if (v.is_null() || (!always && v == s.get(defaults))) continue;
    // A size as suites and manifests spell it ("WxH"); the rest as their JSON form.
    out.push_back(
        {&s, s.type == SettingType::Size ? nlohmann::ordered_json(settingText(r, s)) : v});
  }
  return out;
}

std::vector<std::string> renderArgs(const RenderRequest& r) {
  std::vector<std::string> args = {"strandbench", "render"};
  for (const auto& [s, v] : caseSettings(r)) {
    if (s->type == SettingType::Flag) {
      if (v.get<bool>()) args.push_back(s->flag);
      continue;
    }
    if (s->type == SettingType::References) {
      // Bare for the default reference, once more with each further one's spec.
      if (v.is_boolean()) {
        if (v.get<bool>()) args.push_back(s->flag);
        continue;
      }
      for (const auto& spec : v) {
        args.push_back(s->flag);
        if (spec != "exact") args.push_back(spec.get<std::string>());
      }
      continue;
    }
    args.push_back(s->flag);
    args.push_back(settingText(r, *s));
  }
  return args;
}

// ---- the viewer ----

// The process's resident memory (Linux /proc/self/statm; 0 where unknown): a
// screenshot records it so that a session can be checked for leaks.
std::size_t residentBytes() {
  std::ifstream statm("/proc/self/statm");
  std::size_t pages = 0, resident = 0;
  if (!(statm >> pages >> resident)) return 0;
  return resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

enum class Mode { Technique, Reference, Error };
const char* modeName(Mode m) {
  return m == Mode::Technique ? "technique" : m == Mode::Reference ? "reference" : "error";
}

class Viewer {
 public:
  Viewer(const RenderRequest& req, std::string shotDir) : req_(req), shotDir_(std::move(shotDir)) {
    req_.platform = "window";
    req_.repeat = 1;
    req_.warmup = 0;
    req_.reference = false;
    dev_ = makeRequestDevice(req_);
    window_ = dev_->window();
    // The fitted camera and light, made explicit so they can be moved and written down.
    checkRenderRequest(req_, false, &cache_);
    resetView();
  }

  bool quit = false;

  void handle(const InputEvent& e) {
    switch (e.kind) {
      case InputEvent::Kind::Key:
        if (e.press) key(e);
        break;
      case InputEvent::Kind::Button:
        if (e.press) {
          drag_ = e.button == 2 || (e.button == 0 && e.ctrl)    ? Drag::Pan
                  : e.button == 1 || (e.button == 0 && e.shift) ? Drag::Light
                                                                : Drag::Orbit;
          dragging_ = true;
        } else {
          dragging_ = false;
        }
        break;
      case InputEvent::Kind::Cursor:
        if (dragging_ && haveCursor_) move(e.x - cursorX_, e.y - cursorY_);
        cursorX_ = e.x;
        cursorY_ = e.y;
        haveCursor_ = true;
        break;
      case InputEvent::Kind::Scroll:
        zoom(e.y);
        break;
    }
  }

  // Renders what changed, shows the mode's image and updates the title.
  void update() {
    const uint32_t w = window_->width(), h = window_->height();
    if (w == 0 || h == 0) return;               // minimized
    if (w != req_.width || h != req_.height) {  // the image follows the window
      req_.width = w;
      req_.height = h;
      dirty_ = true;
    }
    if (dirty_) {
      // The shown texture goes first: the render's memory report holds only its own.
      dev_->destroy(display_);
      display_ = {};
      overlay_.release(*dev_);
      RenderRequest r = req_;
      r.reference = mode_ != Mode::Technique || referenceWanted_;
      result_ = runRender(r, &cache_, dev_.get());
      dirty_ = false;
      shownDirty_ = true;
    }
    if (shownDirty_) {
      shown_ = shownImage();
      upload(shown_);
      ++shownVersion_;
      shownDirty_ = false;
    }
    presentShown(nullptr);
    window_->setTitle(title());
  }

  // Shows the mode's image, with the overlay over it when it is on; with
  // `capture`, reads back what the window shows. False while minimized.
  bool presentShown(PresentedImage* capture) {
    const Texture t =
        overlayOn_ ? overlay_.compose(*dev_, display_, shownVersion_, overlayLines()) : display_;
    return dev_->present(t, capture);
  }

  void screenshot(const std::string& name) {
    update();
    const fs::path png = fs::path(shotDir_) / (name + ".png");
    const fs::path json = fs::path(shotDir_) / (name + ".json");
    // The window as shown (the overlay included, when on), beside the image itself.
    const fs::path windowPng = fs::path(shotDir_) / (name + ".window.png");
    PresentedImage window;
    const bool presented = presentShown(&window) && !window.rgba8.empty();
    RenderRequest r = req_;
    r.platform.clear();
    r.reference = mode_ != Mode::Technique;
    std::vector<std::string> args = renderArgs(r);
    const char* outFlag = mode_ == Mode::Technique   ? "--out"
                          : mode_ == Mode::Reference ? "--reference-out"
                                                     : "--heatmap";
    args.push_back(outFlag);
    args.push_back(png.string());
    std::string line;
    for (const auto& a : args) line += (line.empty() ? "" : " ") + shellQuoted(a);
    nlohmann::ordered_json kase = {{"name", name}};
    for (const auto& [s, v] : caseSettings(r)) kase[s->key] = v;
    nlohmann::ordered_json suiteDefaults = kase;
    suiteDefaults.erase("name");
    suiteDefaults.erase("backend");
    suiteDefaults["backends"] = {r.backend};
    nlohmann::ordered_json j;
    j["image"] = png.string();
    j["shown"] = modeName(mode_);
    j["render"] = line;
    j["render_args"] = args;
    j["case"] = kase;
    j["suite"] = {{"name", "view-" + name},
                  {"description", "a view found with strandbench view"},
                  {"defaults", suiteDefaults},
                  {"groups", {{{"name", name}}}}};
    j["title"] = title();
    j["overlay"] = overlayOn_;
    if (overlayOn_) {  // its text, for scripts that check what the window said
      std::vector<std::string> text;
      for (const auto& l : overlayLines())
        text.push_back(l.label.empty() ? l.value : l.label + " " + l.value);
      j["overlay_text"] = text;
    }
    if (presented) j["window_image"] = windowPng.string();
    j["resident_bytes"] = residentBytes();
    j["report"] = renderJson(result_);
    fs::create_directories(shotDir_);
    writeImage(shown_, png.string());
    if (presented) {
      Image shownWindow =
          imageFromRows(window.rgba8, int(window.width), int(window.height), PixelType::UNorm8, 4);
      for (std::size_t i = 3; i < shownWindow.pixels.size(); i += 4) shownWindow.pixels[i] = 1.0f;
      writeImage(shownWindow, windowPng.string());
    }
    const fs::path tmp = json.string() + ".tmp";
    {
      std::ofstream f(tmp);
      f << j.dump(2) << "\n";
      if (!f) throw InputError("cannot write " + json.string());
    }
    fs::rename(tmp, json);
    std::cout << "view: wrote " << png.string() << " and " << json.string() << "\n  " << line
              << "\n";
  }

  void key(const InputEvent& e) {
    const int step = e.shift ? -1 : 1;
    if (e.key == "S") {
      req_.shadow = cycle(Family::Shadow, req_.shadow, step);
    } else if (e.key == "T") {
      req_.oit = cycle(Family::Transparency, req_.oit, step);
    } else if (e.key == "Up" || e.key == "Down") {
      if (!stepped("shadow", req_.shadow, Family::Shadow, e.key == "Up" ? 1 : -1)) return;
    } else if (e.key == "Right" || e.key == "Left") {
      if (!stepped("oit", req_.oit, Family::Transparency, e.key == "Right" ? 1 : -1)) return;
    } else if (e.key == "C") {
      mode_ = Mode((int(mode_) + (e.shift ? 2 : 1)) % 3);
      if (mode_ != Mode::Technique && !referenceWanted_) {
        referenceWanted_ = true;  // from now on the error is known (the reference is cached)
        dirty_ = true;
      }
      shownDirty_ = true;
      return;
    } else if (e.key == "O") {
      overlayOn_ = !overlayOn_;
      std::cout << "view: overlay " << (overlayOn_ ? "on" : "off") << "\n";
      return;
    } else if (e.key == "R") {
      resetView();
    } else if (e.key == "P" || e.key == "F12") {
      char name[32];
      std::snprintf(name, sizeof name, "view-%03d", ++shots_);
      screenshot(name);
      return;
    } else if (e.key == "H") {
      std::cout << kKeys << "\n";
      return;
    } else if (e.key == "Escape" || e.key == "Q") {
      quit = true;
      return;
    } else {
      return;
    }
    std::cout << "view: shadow " << req_.shadow << ", oit " << req_.oit << "\n";
    dirty_ = true;
  }

  // Steps `spec`'s main option; when nothing changes (no such option, or at its
  // limit), says so and returns false: there is nothing to render again.
  static bool stepped(const char* kind, std::string& spec, Family family, int step) {
    const std::string next = stepMain(family, spec, step);
    if (Spec::parse(next).str() != Spec::parse(spec).str()) {  // not merely reordered
      spec = next;
      return true;
    }
    const TechniqueDescriptor* t = tryFindTechnique(family, Spec::parse(spec).name);
    if (!t || !t->stepped)
      std::cout << "view: " << kind << " " << spec
                << " has no option the arrow keys step; unchanged\n";
    else
      std::cout << "view: " << kind << " " << spec << ": " << t->stepped->option << " is at its "
                << (step > 0 ? "largest" : "smallest") << " (" << t->stepped->min << ".."
                << t->stepped->max << "); unchanged\n";
    return false;
  }

  static constexpr const char* kKeys =
      "keys: S / shift+S next / previous shadow technique; T / shift+T next / previous "
      "transparency technique; Up / Down the shadow technique's main option; Right / Left the "
      "transparency technique's; C compare mode (technique, reference, error heatmap; shift+C "
      "back); O overlay (the state over the image) on / off; P or F12 screenshot (PNG + JSON "
      "with the render command); R reset camera and light; H this help; Q or Escape quit. Mouse: "
      "left drag orbit, middle (or ctrl+left) drag "
      "pan, wheel zoom, right (or shift+left) drag moves the light.";

 private:
  enum class Drag { Orbit, Pan, Light };

  void resetView() {
    RenderRequest fitted = req_;
    fitted.view = {};
    const RenderSettings s = makeRenderSettings(fitted, *cache_.scenes.at(req_.scene));
    req_.view.cameraEye = s.camera.eye;
    req_.view.cameraTarget = s.camera.target;
    req_.view.cameraUp = s.camera.up;
    if (!req_.view.lightType) req_.view.lightType = "directional";
    if (req_.view.lightType == "directional")
      req_.view.lightDirection = s.light.direction;
    else
      req_.view.lightPosition = s.light.position;
    dirty_ = true;
  }

  void move(double dx, double dy) {
    glm::vec3& eye = *req_.view.cameraEye;
    glm::vec3& target = *req_.view.cameraTarget;
    const glm::vec3 up = glm::normalize(*req_.view.cameraUp);
    const glm::vec3 offset = eye - target;
    const glm::vec3 right = glm::normalize(glm::cross(-offset, up));
    if (drag_ == Drag::Orbit) {
      eye = target + rotated(offset, up, right, dx, dy);
    } else if (drag_ == Drag::Pan) {
      const float perPixel =
          2.0f * glm::length(offset) * std::tan(glm::radians(fov()) / 2.0f) / float(req_.height);
      const glm::vec3 shift = (-float(dx) * right + float(dy) * up) * perPixel;
      eye += shift;
      target += shift;
    } else if (req_.view.lightDirection) {
      *req_.view.lightDirection =
          glm::normalize(rotated(*req_.view.lightDirection, up, right, dx, dy));
    } else if (req_.view.lightPosition) {
      *req_.view.lightPosition =
          target + rotated(*req_.view.lightPosition - target, up, right, dx, dy);
    }
    dirty_ = true;
  }

  // v turned by dx about `up` and dy about `right` (0.01 rad a pixel), kept off the poles.
  static glm::vec3 rotated(const glm::vec3& v, const glm::vec3& up, const glm::vec3& right,
                           double dx, double dy) {
    glm::vec3 r = glm::vec3(glm::rotate(glm::mat4(1), -0.01f * float(dx), up) * glm::vec4(v, 0));
    const glm::vec3 turned =
        glm::vec3(glm::rotate(glm::mat4(1), -0.01f * float(dy), right) * glm::vec4(r, 0));
    const float c = glm::dot(glm::normalize(turned), up);
    return std::fabs(c) < 0.995f ? turned : r;
  }

  void zoom(double steps) {
    glm::vec3& eye = *req_.view.cameraEye;
    const glm::vec3 target = *req_.view.cameraTarget;
    eye = target + (eye - target) * std::pow(0.9f, float(steps));
    dirty_ = true;
  }

  float fov() const {
    return req_.view.fov ? *req_.view.fov
                         : fitCamera(cache_.scenes.at(req_.scene)->bounds(), 1.0f).fovYDegrees;
  }

  Image shownImage() const {
    if (mode_ == Mode::Technique || result_.referenceImage.pixels.empty()) return result_.image;
    if (mode_ == Mode::Reference) return result_.referenceImage;
    return diffHeatmap(result_.image, result_.referenceImage, 0.25);
  }

  // An RGBA32F texture the window's size holding `img` (rows bottom-up).
  void upload(const Image& img) {
    if (!display_ || dev_->describe(display_).width != uint32_t(img.width) ||
        dev_->describe(display_).height != uint32_t(img.height)) {
      dev_->destroy(display_);
      display_ = dev_->createTexture({"view.display", Owner::View, Format::RGBA32F,
                                      uint32_t(img.width), uint32_t(img.height)});
    }
    std::vector<float> rows(std::size_t(img.width) * img.height * 4, 1.0f);
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        for (int c = 0; c < std::min(img.channels, 4); ++c)
          rows[(std::size_t(img.height - 1 - y) * img.width + x) * 4 + c] =
              img.pixels[(std::size_t(y) * img.width + x) * img.channels + c];
    std::vector<uint8_t> bytes(rows.size() * sizeof(float));
    std::memcpy(bytes.data(), rows.data(), bytes.size());
    dev_->writeTexture(display_, bytes);
  }

  // The timed frame's slowest pass (null before any render).
  const PassTimes* slowestPass() const {
    const PassTimes* slowest = nullptr;
    for (const auto& p : result_.passes)
      if (!p.ms.empty() && (!slowest || p.ms.front() > slowest->ms.front())) slowest = &p;
    return slowest;
  }

  // The render's device memory (the viewer's own textures not counted).
  std::size_t renderBytes() const {
    std::size_t bytes = 0;
    for (const auto& r : result_.resources)
      if (r.owner != Owner::View) bytes += r.bytes;
    return bytes;
  }

  // What the overlay says: the title's state, a line each. Times and memory
  // are always the technique's run (the reference is rendered untimed), so
  // when the reference or the error is shown the overlay says so in amber.
  std::vector<OverlayLine> overlayLines() const {
    const std::array<uint8_t, 3> amber{255, 196, 64}, dim{150, 150, 150};
    auto number = [](double v, const char* unit) {
      char text[48];
      std::snprintf(text, sizeof text, "%.2f %s", v, unit);
      return std::string(text);
    };
    std::vector<OverlayLine> l;
    if (mode_ == Mode::Technique) {
      l.push_back({"", result_.device.backend + " | technique"});
    } else {
      // Short lines (a spec each): a 400-pixel window holds them at 1x.
      l.push_back({"",
                   result_.device.backend + " | " +
                       (mode_ == Mode::Reference ? "REFERENCE shown (untimed)"
                                                 : "ERROR heatmap: technique vs reference"),
                   amber});
      if (result_.reference) {
        l.push_back({"ref shadow", result_.reference->first, amber});
        l.push_back({"ref oit", result_.reference->second, amber});
      }
      l.push_back({"", "below: the technique's specs, times, memory", amber});
    }
    l.push_back({"shadow", result_.shadow});
    l.push_back({"oit", result_.oit});
    l.push_back({"shading", result_.shading});
    if (!result_.frameMs.empty()) l.push_back({"frame", number(result_.frameMs.front(), "ms")});
    if (const PassTimes* slowest = slowestPass())
      l.push_back({"slowest", slowest->name + "  " + number(slowest->ms.front(), "ms")});
    l.push_back({"memory", number(double(renderBytes()) / (1 << 20), "MiB")});
    if (result_.imageError)
      l.push_back({"PSNR", result_.imageError->identical()
                               ? std::string("identical to the reference")
                               : number(result_.imageError->psnr, "dB") + " vs the reference"});
    l.push_back({"", "press o to hide", dim});  // lower case: stb draws O as 0
    return l;
  }

  std::string title() const {
    std::ostringstream t;
    t.precision(3);
    t << "strandbench view | " << result_.device.backend << " | shadow " << result_.shadow
      << " | oit " << result_.oit << " | " << modeName(mode_);
    if (!result_.frameMs.empty()) t << " | frame " << result_.frameMs.front() << " ms";
    if (const PassTimes* slowest = slowestPass())
      t << " | slowest " << slowest->name << " " << slowest->ms.front() << " ms";
    t << " | " << double(renderBytes()) / (1 << 20) << " MiB";
    if (result_.imageError) {
      if (result_.imageError->identical())
        t << " | identical to reference";
      else
        t << " | PSNR " << result_.imageError->psnr << " dB vs reference";
    }
    return t.str();
  }

  RenderRequest req_;
  std::string shotDir_;
  std::unique_ptr<Device> dev_;
  Window* window_ = nullptr;
  RenderCache cache_;
  RenderResult result_;
  Image shown_;
  Texture display_;
  uint64_t shownVersion_ = 0;  // bumped at each upload into display_: the overlay composes again
  ViewOverlay overlay_;
  bool overlayOn_ = true;
  Mode mode_ = Mode::Technique;
  bool referenceWanted_ = false;
  bool dirty_ = true, shownDirty_ = true;
  Drag drag_ = Drag::Orbit;
  bool dragging_ = false, haveCursor_ = false;
  double cursorX_ = 0, cursorY_ = 0;
  int shots_ = 0;

 public:
  Window& window() { return *window_; }
};

InputEvent keyEvent(const ScriptAction& a) {
  InputEvent e;
  e.kind = InputEvent::Kind::Key;
  e.key = a.args[0];
  for (std::size_t i = 1; i < a.args.size(); ++i) {
    e.shift |= a.args[i] == "shift";
    e.ctrl |= a.args[i] == "ctrl";
    e.alt |= a.args[i] == "alt";
  }
  return e;
}

// A drag as the window would report it: press at the centre, one move, release.
std::vector<InputEvent> dragEvents(const ScriptAction& a, Window& w) {
  InputEvent at;
  at.kind = InputEvent::Kind::Cursor;
  at.x = w.width() / 2.0;
  at.y = w.height() / 2.0;
  InputEvent press;
  press.kind = InputEvent::Kind::Button;
  press.button = a.args[0] == "left" ? 0 : a.args[0] == "right" ? 1 : 2;
  for (std::size_t i = 3; i < a.args.size(); ++i) {
    press.shift |= a.args[i] == "shift";
    press.ctrl |= a.args[i] == "ctrl";
  }
  InputEvent to = at;
  to.x += std::stod(a.args[1]);
  to.y += std::stod(a.args[2]);
  InputEvent release = press;
  release.press = false;
  return {at, press, to, release};
}

int runView(const RenderRequest& req, const std::string& scriptPath, const std::string& shotDir) {
  std::vector<ScriptAction> script;
  if (!scriptPath.empty()) script = parseScript(scriptPath);
  Viewer viewer(req, shotDir);
  std::cout << Viewer::kKeys << "\n";
  const auto start = Clock::now();
  std::size_t next = 0;
  while (!viewer.quit && !viewer.window().closeRequested()) {
    for (const InputEvent& e : viewer.window().poll()) viewer.handle(e);
    const double now = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    // Each due action is applied and the view brought up to date before the
    // next, so a screenshot shows every action before it.
    while (next < script.size() && script[next].atMs <= now && !viewer.quit) {
      const ScriptAction& a = script[next++];
      if (a.action == "key") {
        viewer.handle(keyEvent(a));
      } else if (a.action == "drag") {
        for (const InputEvent& e : dragEvents(a, viewer.window())) viewer.handle(e);
      } else if (a.action == "scroll") {
        InputEvent e;
        e.kind = InputEvent::Kind::Scroll;
        e.y = std::stod(a.args[0]);
        viewer.handle(e);
      } else if (a.action == "resize") {
        viewer.window().resize(uint32_t(std::stoul(a.args[0])), uint32_t(std::stoul(a.args[1])));
      } else if (a.action == "screenshot") {
        viewer.screenshot(a.args[0]);
      } else if (a.action == "quit") {
        viewer.quit = true;
      }
      if (!viewer.quit) viewer.update();
    }
    if (viewer.quit) break;
    viewer.update();
    std::this_thread::sleep_for(std::chrono::milliseconds(15));
  }
  return 0;
}

}  // namespace

void registerViewCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "view",
      "look at a scene in a window: orbit, move the light, switch techniques, compare "
      "with the reference, save a screenshot with its render command (needs a display)");
  auto req = std::make_shared<RenderRequest>();
  req->width = req->height = 512;
  // The settings of the picture (not timing, measurement or the platform: always a window).
  std::vector<std::string> keys = {"scene",   "shadow", "oit",       "shading",      "msaa",
                                   "backend", "size",   "primitive", "ribbon_width", "validation"};
  for (std::string& k : viewSettingKeys()) keys.push_back(std::move(k));
  auto settings = std::make_shared<CliSettings>(*cmd, keys, *req);
  auto script = std::make_shared<std::string>();
  auto shotDir = std::make_shared<std::string>(".");
  cmd->add_option("--script", *script,
                  "play a timed list of actions (" + std::string(kScriptHelp) + ")");
  cmd->add_option("--screenshot-dir", *shotDir, "where screenshots (PNG + JSON) go")
      ->capture_default_str();
  cmd->callback([=] {
    runGuarded("view", [&] {
      settings->apply(*req);
      checkOutputFolder("--screenshot-dir", *shotDir);
      // Any key may take a screenshot: the image module is loaded at the start, so that
      // the session's resident memory does not jump at its first screenshot.
      loadImageModule();
      return runView(*req, *script, *shotDir);
    });
  });
}

}  // namespace sb
