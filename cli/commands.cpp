#include "cli/commands.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <iostream>
#include <memory>
#include <new>

#include "backends/device.h"
#include "backends/driver_env.h"
#include "base/options.h"
#include "cli/render_summary.h"
#include "harness/measures/animation/animation.h"
#include "harness/reference_spec.h"
#include "harness/render.h"
#include "harness/settings.h"
#include "harness/stop.h"
#include "harness/technique_list.h"
#include "imaging/flip.h"
#include "imaging/image.h"
#include "imaging/metrics.h"
#include "render/common/technique.h"
#include "reports/files.h"
#include "scenes/scene.h"

namespace sb {
namespace {

namespace fs = std::filesystem;

int gStatus = 0;

void printOptions(const std::vector<OptionInfo>& options) {
  for (const auto& o : options)
    std::cout << "      " << o.name << "=" << o.defaultValue << "  " << o.help << "\n";
}

constexpr Family kFamilies[] = {Family::Shadow, Family::Transparency, Family::Shading};

// `list NAME`: every technique of that name (none and occupancy are in two families).
int listOne(const std::string& name) {
  std::vector<std::string> names;
  bool found = false;
  for (Family f : kFamilies)
    for (const TechniqueDescriptor* d : techniques(f)) {
      names.push_back(d->name);
      if (d->name != name) continue;
      std::cout << heading(f) << " (--" << familyFlag(f) << " " << name << ":key=value,...):\n";
      printTechnique(std::cout, *d, true);
      found = true;
    }
  if (!found) throw InputError(unknownNameMessage("technique", name, names));
  return 0;
}

void registerList(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "list", "list scenes, techniques, their options and defaults (list NAME: one technique)");
  auto json = std::make_shared<bool>(false);
  auto markdown = std::make_shared<bool>(false);
  auto techniquesMd = std::make_shared<bool>(false);
  auto name = std::make_shared<std::string>();
  cmd->add_option("name", *name, "a technique or shading model: show it alone, in detail");
  cmd->add_flag("--json", *json, "print as JSON");
  cmd->add_flag("--settings-markdown", *markdown,
                "print only the render settings as the Markdown table of the docs");
  cmd->add_flag("--markdown", *techniquesMd,
                "print docs/techniques.md (strandbench list --markdown > docs/techniques.md)");
  cmd->callback([json, markdown, techniquesMd, name] {
    runGuarded("list", [&] {
      if (*markdown) {
        std::cout << settingsMarkdown();
        return 0;
      }
      if (*techniquesMd) {
        std::cout << techniquesMarkdown();
        return 0;
      }
      if (!name->empty() && !*json) return listOne(*name);
      if (*json) {
        nlohmann::json j;
        if (!name->empty()) {
          for (Family f : kFamilies)
            if (const TechniqueDescriptor* d = tryFindTechnique(f, *name))
              j[familyFlag(f)].push_back(techniqueJson(*d));
          if (j.is_null()) listOne(*name);  // throws the unknown-name error
          std::cout << j.dump(2) << "\n";
          return 0;
        }
        for (const auto& s : sceneCatalog())
          j["scenes"].push_back(
              {{"name", s.name}, {"help", s.help}, {"options", optionsJson(s.options)}});
        for (Family f : kFamilies)
          for (const TechniqueDescriptor* d : techniques(f))
            j[familyFlag(f)].push_back(techniqueJson(*d));
        for (const auto& b : backendCatalog())
          j["backends"].push_back({{"name", b.name}, {"platforms", b.platforms}});
        j["primitives"] = findSetting("primitive")->choices;
        j["settings"] = settingsJson();
        std::cout << j.dump(2) << "\n";
        return 0;
      }
      std::cout << "scenes (--scene NAME:key=value,...):\n";
      for (const auto& s : sceneCatalog()) {
        std::cout << "  " << s.name << "  " << s.help << "\n";
        printOptions(s.options);
      }
      for (Family f : kFamilies) {
        std::cout << heading(f) << " (--" << familyFlag(f) << " NAME:key=value,...):\n";
        for (const TechniqueDescriptor* d : techniques(f)) printTechnique(std::cout, *d, false);
      }
      std::cout << "backends (--backend):";
      for (const auto& b : backendCatalog()) {
        std::cout << (&b == &backendCatalog().front() ? " " : ", ") << b.name << " (--platform";
        for (const auto& p : b.platforms)
          std::cout << (&p == &b.platforms.front() ? " " : "|") << p;
        std::cout << ")";
      }
      std::cout << "\nprimitives (--primitive): lines, ribbons (--ribbon-width PIXELS)\n"
                << "render settings (CLI flag / suite and manifest key, type, range, default):\n"
                << settingsText();
      return 0;
    });
  });
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
  auto settings = std::make_shared<CliSettings>(*cmd, std::vector<std::string>{}, *req);
  auto out = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto referenceOut = std::make_shared<std::string>();
  auto heatmap = std::make_shared<std::string>();
  auto flipMap = std::make_shared<std::string>();
  auto strip = std::make_shared<std::string>();
  auto trace = std::make_shared<std::string>();
  cmd->add_option("--trace", *trace,
                  "write the timed frames' passes as a Chrome/Perfetto trace (.json; open in "
                  "ui.perfetto.dev or chrome://tracing)");
  cmd->add_option("--reference-out", *referenceOut,
                  "with --reference: write the reference asked for (the exact one; with "
                  "only further ones, the first of those); each other one asked for beside "
                  "it, its name before the extension (ref.png: ref.NAME.png)");
  cmd->add_option("--strip", *strip,
                  "with --animate: write up to four frames side by side, the technique's above "
                  "the reference's");
  cmd->add_option("--heatmap", *heatmap,
                  "with --reference: write a heatmap of |image - reference| (full scale 0.25)");
  cmd->add_option("--flip-map", *flipMap,
                  "with --reference: write FLIP's error map of the image (magma)");
  cmd->add_option("--out", *out, "image file (.png 8-bit, .exr float)");
  cmd->add_flag("--json", *json, "print the report as one JSON object on stdout");
  cmd->callback([=] {
    runGuarded("render", [&] {
      settings->apply(*req);
      if (!out->empty()) checkOutputPath("--out", *out, {".png", ".exr"});
      if (!trace->empty()) checkOutputPath("--trace", *trace, {".json"});
      req->timeline = !trace->empty();
      if (!req->image && (!out->empty() || !referenceOut->empty() || !heatmap->empty() ||
                          !flipMap->empty() || !strip->empty()))
        throw InputError(
            "--no-image writes no images: drop --out, --reference-out, --heatmap, --flip-map and "
            "--strip");
      if (!strip->empty()) {
        if (!req->animate) throw InputError("--strip needs --animate");
        checkOutputPath("--strip", *strip, {".png", ".exr"});
      }
      for (const auto& [option, extra] :
           {std::pair{"--reference-out", referenceOut.get()}, std::pair{"--heatmap", heatmap.get()},
            std::pair{"--flip-map", flipMap.get()}}) {
        if (extra->empty()) continue;
        if (!req->reference)
          throw InputError("--reference-out, --heatmap and --flip-map need --reference");
        checkOutputPath(option, *extra, {".png", ".exr"});
      }
      RenderCache cache;  // the scene, built once by the check
      if (!out->empty() || !referenceOut->empty() || !heatmap->empty() || !flipMap->empty() ||
          !strip->empty())
        loadImageModule();
      checkRenderRequest(*req, false, &cache);
      const RenderResult result = runRender(*req, &cache);
      // The run's files all or none: one that fails (out of memory) or a stop
      // between them takes back those already written.
      std::vector<std::string> written;
      auto write = [&](const std::string& path, const auto& makeImage) {
        if (path.empty()) return;
        throwIfStopped();
        writeImage(makeImage(), path);  // atomic: a temporary file renamed into place
        written.push_back(path);
      };
      try {
        write(*out, [&]() -> const Image& { return result.image; });
        // --reference-out holds the reference the user asked for: the exact one when
        // named (bare --reference, or exact), else the first further one; the exact one
        // is then rendered only to measure against, and not written.
        const CLI::Option* asked = cmd->get_option("--reference");
        bool exactAsked = asked->results().size() < asked->count();  // bare, no value
        for (const std::string& t : asked->results())
          exactAsked |= t.empty() || parseReferenceSpec(t).name == defaultReference().name;
        std::vector<std::pair<std::string, const Image*>> refs;  // name, image
        if (exactAsked || result.moreReferences.empty())
          refs.emplace_back("exact", &result.referenceImage);
        for (const RenderResult::MoreReference& m : result.moreReferences)
          refs.emplace_back(m.name, &m.referenceImage);
        if (!referenceOut->empty()) {
          const fs::path p(*referenceOut);
          for (std::size_t i = 0; i < refs.size(); ++i)
            write(i == 0 ? p.string()
                         : (p.parent_path() /
                            (p.stem().string() + "." + refs[i].first + p.extension().string()))
                               .string(),
                  [&]() -> const Image& { return *refs[i].second; });
        }
        write(*heatmap, [&] { return diffHeatmap(result.image, result.referenceImage, 0.25); });
        write(*flipMap, [&] { return flipErrorImage(*result.flip); });
        write(*strip, [&] { return animationStrip(*result.measure<AnimationResult>()); });
        if (!trace->empty()) {
          writeFileAtomic(*trace, traceJson(result).dump() + "\n");
          written.push_back(*trace);
        }
        throwIfStopped();
      } catch (...) {
        std::error_code ec;
        for (const auto& path : written) fs::remove(path, ec);
        throw;
      }
      nlohmann::json report = renderJson(result);
      if (!out->empty()) report["image"] = *out;
      if (*json) {
        // stdout is the JSON (its "warnings" too); a person sees them on stderr.
        for (const auto& w : result.warnings)
          std::cerr << "strandbench render: warning: " << w << "\n";
        std::cout << report.dump(2) << "\n";
        return 0;
      }
      printRenderSummary(std::cout, *req, result);
      if (!out->empty()) std::cout << "  wrote " << *out << "\n";
      return 0;
    });
  });
}

void registerCompare(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("compare", "image error between two files (RMSE, PSNR, SSIM, FLIP)");
  auto a = std::make_shared<std::string>();
  auto b = std::make_shared<std::string>();
  cmd->add_option("A", *a, "first image")->required();
  cmd->add_option("B", *b, "second image")->required();
  auto heatmap = std::make_shared<std::string>();
  auto scale = std::make_shared<double>(0.25);
  auto flipMap = std::make_shared<std::string>();
  auto ppd = std::make_shared<double>(kFlipDefaultPpd);
  cmd->add_option("--heatmap", *heatmap, "write a viridis heatmap of |A - B| (PNG or EXR)");
  cmd->add_option("--heatmap-scale", *scale, "difference shown as the top colour")
      ->capture_default_str();
  cmd->add_option("--flip-map", *flipMap,
                  "write FLIP's error map of A against the reference B (magma, PNG or EXR)");
  cmd->add_option("--ppd", *ppd, "FLIP: the observer's pixels per degree of visual angle")
      ->capture_default_str();
  cmd->callback([=] {
    runGuarded("compare", [&] {
      if (!heatmap->empty()) {
        if (!(*scale > 0)) throw InputError("--heatmap-scale must be positive");
        checkOutputPath("--heatmap", *heatmap, {".png", ".exr"});
      }
      if (!(*ppd > 0 && *ppd <= kFlipMaxPpd))
        throw InputError("--ppd " + std::to_string(*ppd) +
                         ": pixels per degree must be positive, at most 1000");
      if (!flipMap->empty()) checkOutputPath("--flip-map", *flipMap, {".png", ".exr"});
      const int status =
          runCompareCommand(*a, *b, std::cout, std::cerr, 1.0 / 255.0, *ppd, *flipMap);
      if (status == 0 && !heatmap->empty())
        writeImage(diffHeatmap(readImage(*a), readImage(*b), *scale), *heatmap);
      return status;
    });
  });
}

}  // namespace

// `docs refresh` and `docs check` (cli/docs_command.cpp).
void registerDocsCommands(CLI::App& app);

void registerCommands(CLI::App& app) {
  registerList(app);
  registerRender(app);
  registerCompare(app);
  registerCheckCommands(app);
  registerProbeCommand(app);
  registerBenchCommand(app);
  registerSweepCommands(app);
  registerCompareRunsCommand(app);
  registerHistoryCommand(app);
  registerViewCommand(app);
  registerFigureCommand(app);
  registerBsdfProbeCommand(app);
  registerDocsCommands(app);  // cli/docs_command.cpp
  // Unknown options get the closest valid one, for every command.
  for (CLI::App* cmd : app.get_subcommands([](CLI::App*) { return true; }))
    cmd->parse_complete_callback([cmd] { rejectUnknownArguments(*cmd); });
}

void addDriverOption(CLI::App& cmd) {
  static std::deque<std::string> values;  // CLI11 keeps a reference to each
  values.emplace_back();
  cmd.add_option("--driver", values.back(), kDriverHelp);
}

int lastCommandStatus() { return gStatus; }

std::string parseErrorMessage(const CLI::App& app, const CLI::ParseError& error,
                              const std::vector<std::string>& args) {
  // A first word that names no command: CLI11 says only that a subcommand is required.
  if (!args.empty() && !args[0].empty() && args[0][0] != '-' && app.get_subcommands().empty()) {
    std::vector<std::string> names;
    for (const CLI::App* cmd : app.get_subcommands([](const CLI::App*) { return true; }))
      names.push_back(cmd->get_name());
    return "strandbench: " + unknownNameMessage("command", args[0], names);
  }
  // A flag that takes one value, given more than once: CLI11 says "--size: At Most 1
  // required but received 2".
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&error)) {
    for (const CLI::App* cmd : app.get_subcommands())
      for (const CLI::Option* o : cmd->get_options()) {
        if (o->count() < 2 || o->get_multi_option_policy() != CLI::MultiOptionPolicy::Throw ||
            o->get_items_expected_max() > 1)
          continue;
        std::string values;
        for (const std::string& v : o->results()) values += (values.empty() ? "" : ", ") + v;
        return "strandbench " + cmd->get_name() + ": " + o->get_name() + " given " +
               std::to_string(o->count()) + " times (" + values + "): give it once";
      }
  }
  return std::string("strandbench: ") + error.what();
}

void runGuarded(const char* command, const std::function<int()>& body) {
  auto fail = [&](const std::string& message, int status) {
    std::cerr << "strandbench " << command << ": " << message << "\n";
    gStatus = status;
  };
  // Every exception ends here, never in std::terminate.
  try {
    gStatus = body();
  } catch (const InputError& e) {
    fail(e.what(), 2);
  } catch (const DeviceError& e) {  // OutOfMemoryError included
    fail(e.what(), 2);
  } catch (const Interrupted& e) {
    fail(std::string(e.what()) + "; no partial file was left", 128 + e.signal);
  } catch (const std::bad_alloc&) {
    // Allocations the device and the image writer know name themselves
    // (OutOfMemoryError); this is any other host allocation.
    fail("out of memory: a host allocation failed (no size known here); nothing was written", 2);
  } catch (const std::exception& e) {
    fail(std::string("internal error: ") + e.what(), 2);
  }
}

}  // namespace sb
