#include "harness/case_store.h"

#include <unistd.h>

#include <iostream>
#include <tuple>

#include "backends/driver_env.h"
#include "base/errors.h"
#include "base/fnv.h"
#include "base/options.h"
#include "harness/run_context.h"
#include "harness/settings.h"
#include "render/common/unit.h"
#include "reports/files.h"
#include "reports/json_file.h"
#include "scenes/scene.h"

namespace sb {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

namespace {

constexpr int kFormat = 1;

// A spec with every option its descriptor has, the defaults filled in and numbers written
// one way ("0.50" and ".5" are one option), so "occupancy" and "occupancy:jitter=off" (its
// default) are one case.
std::string canonicalSpec(const std::string& text, const std::vector<OptionInfo>* options) {
  Spec spec = Spec::parse(text);
  if (!options) return spec.str();
  for (const OptionInfo& o : *options) {
    auto it = spec.options.find(o.name);
    if (it == spec.options.end()) {
      if (!o.defaultValue.empty()) spec.options[o.name] = o.defaultValue;
      continue;
    }
    if (o.kind == OptionKind::Integer || o.kind == OptionKind::Number) {
      try {
        std::size_t used = 0;
        const double v = std::stod(it->second, &used);
        if (used == it->second.size()) it->second = shortestNumber(v);
      } catch (const std::exception&) {
        // not a number: kept as written (the run refuses it)
      }
    }
  }
  return spec.str();
}

const std::vector<OptionInfo>* sceneOptions(const std::string& name) {
  for (const SceneInfo& s : sceneCatalog())
    if (s.name == name) return &s.options;
  return nullptr;
}

const std::vector<OptionInfo>* techniqueOptions(Family f, const std::string& name) {
  const TechniqueDescriptor* d = tryFindTechnique(f, name);
  return d ? &d->options : nullptr;
}

fs::path entryDir(const fs::path& dir, const std::string& key) {
  return dir / hex64(fnv1a(kFnvOffset, key.data(), key.size()));
}

// "images/<from>.heatmap.png" -> "images/<to>.heatmap.png"; "" when `rel` is not one of
// `from`'s files.
std::string renamed(const std::string& rel, const std::string& folder, const std::string& from,
                    const std::string& to) {
  const std::string prefix = folder + "/" + from;
  if (rel.rfind(prefix, 0) != 0 || rel.find("..") != std::string::npos) return "";
  return folder + "/" + to + rel.substr(prefix.size());
}

}  // namespace

CaseStore::CaseStore(fs::path dir) : dir_(std::move(dir)) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (!fs::is_directory(dir_))
    throw InputError("--cases " + dir_.string() + ": cannot create the folder (" + ec.message() +
                     ")");
  const nlohmann::json context = runContext();
  // The binary that runs: a rebuild (any code change that can run) gives another key.
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  const auto size = ec ? 0 : fs::file_size(exe, ec);
  const auto time = ec ? 0 : fs::last_write_time(exe, ec).time_since_epoch().count();
  code_ = {{"commit", context.value("commit", nlohmann::json(nullptr))},
           {"dirty", context.value("commit_dirty", false)},
           {"executable", {{"path", exe.string()}, {"size", size}, {"time", time}}},
           {"driver", currentDriver()}};
  machine_ = {{"date", context.value("date", "")},
              {"cpu", context.value("cpu", "")},
              {"load_before", context.value("load_before", nlohmann::json(nullptr))}};
}

std::string CaseStore::key(const SweepCase& c, const RepetitionOptions& rounds,
                           bool interleave) const {
  ojson settings = ojson::object();
  for (const Setting& s : settingsTable()) settings[s.key] = s.get(c.request);
  const RenderRequest& q = c.request;
  settings["scene"] = canonicalSpec(q.scene, sceneOptions(Spec::parse(q.scene).name));
  for (const auto& [k, family, spec] : {std::tuple{"shadow", Family::Shadow, q.shadow},
                                        std::tuple{"oit", Family::Transparency, q.oit},
                                        std::tuple{"shading", Family::Shading, q.shading}})
    settings[k] = canonicalSpec(spec, techniqueOptions(family, Spec::parse(spec).name));
  settings["run_to_run"] = q.runToRun;
  // Interleaved, a case's frames are its rounds (below); its `repeat` only set their default.
  if (interleave) settings.erase("repeat");
  const ojson key = {{"format", kFormat},
                     {"settings", settings},
                     {"rounds",
                      {{"interleaved", interleave},
                       {"min", rounds.minReps},
                       {"max", rounds.maxReps},
                       {"target_ci_pct", rounds.targetCiPct}}},
                     {"code", code_}};
  return key.dump();
}

std::optional<ojson> CaseStore::take(const std::string& key, const fs::path& sweepDir,
                                     const SweepCase& c) const {
  const fs::path entry = entryDir(dir_, key);
  ojson stored;
  try {
    stored = readJsonFile<ojson>(entry / "entry.json");
  } catch (const InputError&) {
    return std::nullopt;  // none, or damaged
  }
  if (!stored.is_object() || stored.value("format", 0) != kFormat ||
      stored.value("key", "") != key || !stored.contains("result") || !stored["result"].is_object())
    return std::nullopt;  // another case under the same hash, or not an entry
  const std::string from = stored.value("stem", "");
  ojson result = stored["result"];
  if (from.empty() || result.contains("failed")) return std::nullopt;
  // Every file first, then the copies: a damaged entry writes nothing.
  std::vector<std::pair<fs::path, fs::path>> copies;
  auto add = [&](ojson& rel, const std::string& folder) {
    if (!rel.is_string()) return false;
    const std::string to = renamed(rel.get<std::string>(), folder, from, c.stem);
    if (to.empty() || !fs::is_regular_file(entry / rel.get<std::string>())) return false;
    copies.emplace_back(entry / rel.get<std::string>(), sweepDir / to);
    rel = to;
    return true;
  };
  for (auto& [kind, rel] : result["images"].items())
    if (!add(rel, "images")) return std::nullopt;
  if (result.contains("trace") && !add(result["trace"], "traces")) return std::nullopt;
  std::error_code ec;
  for (const auto& [src, dst] : copies) {
    fs::create_directories(dst.parent_path(), ec);
    if (!fs::copy_file(src, dst, fs::copy_options::overwrite_existing, ec)) return std::nullopt;
  }
  result["case"] = {{"id", c.id}, {"group", c.group}, {"index", c.index}, {"params", c.params}};
  result["shared"] = {{"measured_for", stored.value("measured_for", "")},
                      {"case", stored.value("case", "")},
                      {"entry", entry.filename().string()},
                      {"context", stored.value("context", ojson::object())}};
  return result;
}

bool CaseStore::put(const std::string& key, const fs::path& sweepDir, const SweepCase& c,
                    const ojson& result, const std::string& measuredFor) const {
  if (result.contains("failed") || result.contains("shared")) return false;
  const fs::path entry = entryDir(dir_, key);
  // Written beside it and renamed: an entry is there whole or not at all.
  const fs::path tmp =
      dir_ / ("." + entry.filename().string() + ".tmp-" + std::to_string(::getpid()));
  std::error_code ec;
  fs::remove_all(tmp, ec);
  try {
    std::vector<std::string> files;
    const ojson images = result.value("images", ojson::object());
    for (const auto& [kind, rel] : images.items()) files.push_back(rel.get<std::string>());
    if (result.contains("trace")) files.push_back(result["trace"].get<std::string>());
    for (const std::string& rel : files) {
      fs::create_directories((tmp / rel).parent_path());
      fs::copy_file(sweepDir / rel, tmp / rel);
    }
    ojson context = machine_;
    context["load_after"] = loadAverage();  // when the case was done
    const ojson stored = {{"format", kFormat}, {"key", key},     {"measured_for", measuredFor},
                          {"case", c.id},      {"stem", c.stem}, {"context", context},
                          {"result", result}};
    writeFileAtomic(tmp / "entry.json", stored.dump(1) + "\n");
    // One already there with this key stays (another sweep stored it first); a damaged one,
    // or another key's under the same hash, is replaced.
    if (fs::exists(entry)) {
      bool same = false;
      try {
        same = readJsonFile<ojson>(entry / "entry.json").value("key", "") == key;
      } catch (const InputError&) {
      }
      if (same) {
        fs::remove_all(tmp, ec);
        return true;
      }
      fs::remove_all(entry);
    }
    fs::rename(tmp, entry);
    return true;
  } catch (const fs::filesystem_error& e) {
    // A case not kept is measured again by the next sweep that needs it: worth a line, not a
    // failure.
    std::cerr << "case store " << dir_.string() << ": case " << c.id << " not kept (" << e.what()
              << ")\n";
    fs::remove_all(tmp, ec);
    return false;
  }
}

}  // namespace sb
