// A figure run (harness/figure.h): the figure's suite is swept into a temporary folder, the
// grid image is composed with OpenImageIO (fit, paste, text: imaging/oiio/) and figure.md /
// figure.json are written (reports/figure_report.h), then the folder is renamed into place,
// so a stopped or failed run leaves nothing half written. cli/figure_command.cpp parses.
#include "harness/figure.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <set>

#include "base/errors.h"
#include "base/options.h"
#include "harness/backend_names.h"
#include "harness/checks.h"
#include "harness/run_context.h"
#include "harness/sweep.h"
#include "imaging/image.h"
#include "imaging/metrics.h"
#include "imaging/oiio/oiio_api.h"
#include "render/common/unit.h"
#include "reports/figure_report.h"
#include "reports/files.h"
#include "reports/json_file.h"
#include "reports/report_data.h"

namespace sb {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

namespace {

constexpr const char* kModelsPrefix = "../shared/models/";

// Every string under `j` with "../shared/models/" replaced by the models folder, so a figure
// runs from any working directory (a plain `sweep` of the file runs from the source tree).
void resolveModels(ojson& j, const std::string& dir) {
  if (j.is_string()) {
    std::string s = j.get<std::string>();
    for (std::size_t p = s.find(kModelsPrefix); p != std::string::npos;
         p = s.find(kModelsPrefix, p + dir.size()))
      s.replace(p, std::string(kModelsPrefix).size(), dir);
    j = s;
  } else if (j.is_structured()) {
    for (auto& v : j) resolveModels(v, dir);
  }
}

// Sets each key of `patch` in `target` (an object): the "small" block's overrides.
void overlay(ojson& target, const ojson& patch, const std::string& where) {
  if (!patch.is_object()) throw InputError(where + " must be an object");
  for (const auto& [k, v] : patch.items()) target[k] = v;
}

// "small": {"defaults": {...}, "presets": {NAME: {...}}, "groups": {NAME: {...}}}: each
// object's keys set in the suite's defaults, the named preset, the named group.
void applySmall(ojson& doc, const std::string& where) {
  if (!doc.contains("small"))
    throw InputError(where + ": --small: the figure has no \"small\" block");
  const ojson& s = doc["small"];
  if (!s.is_object()) throw InputError(where + ": \"small\" must be an object");
  for (const auto& [key, value] : s.items()) {
    const std::string w = where + ": \"small\"." + key;
    if (key == "defaults") {
      if (!doc.contains("defaults")) doc["defaults"] = ojson::object();
      overlay(doc["defaults"], value, w);
    } else if (key == "presets" || key == "groups") {
      if (!value.is_object()) throw InputError(w + " must be an object of names");
      for (const auto& [name, patch] : value.items()) {
        ojson* target = nullptr;
        if (key == "presets" && doc.contains("presets") && doc["presets"].contains(name))
          target = &doc["presets"][name];
        if (key == "groups" && doc.contains("groups") && doc["groups"].is_array())
          for (auto& g : doc["groups"])
            if (g.value("name", "") == name) target = &g;
        if (!target) throw InputError(w + ": \"" + name + "\" is not one of the suite's " + key);
        overlay(*target, patch, w + "." + name);
      }
    } else {
      throw InputError(w + ": unknown key (known: defaults, presets, groups)");
    }
  }
}

// Every case on the figure's backends: the default's "backends", no other layer naming one.
void onBackends(ojson& doc, const std::vector<std::string>& backends) {
  auto strip = [](ojson& layer) {
    if (!layer.is_object()) return;
    layer.erase("backend");
    layer.erase("backends");
    if (layer.contains("axes") && layer["axes"].is_object()) layer["axes"].erase("backend");
  };
  if (!doc.contains("defaults")) doc["defaults"] = ojson::object();
  strip(doc["defaults"]);
  doc["defaults"]["backends"] = backends;
  if (doc.contains("presets") && doc["presets"].is_object())
    for (auto& [name, p] : doc["presets"].items()) strip(p);
  if (doc.contains("groups") && doc["groups"].is_array())
    for (auto& g : doc["groups"]) strip(g);
}

fs::path figureFile(const std::string& name) {
  if (name.ends_with(".json")) {
    if (!fs::is_regular_file(name)) throw InputError("figure " + name + ": no such file");
    return name;
  }
  const fs::path p = figuresDir() / (name + ".json");
  if (!fs::is_regular_file(p))
    throw InputError("figure " + name + ": " + unknownNameMessage("figure", name, figureNames()) +
                     " (strandbench figure --list)");
  return p;
}

std::string figureName(const std::string& name) {
  return name.ends_with(".json") ? fs::path(name).stem().string() : name;
}

// --- the grid image ---

struct Layout {
  int tile = 256, gap = 4, margin = 12, title = 34, header = 26, label = 170, caption = 20;
  int rows = 0, columns = 0;
  int cellWidth() const { return 2 * tile + gap; }
  int cellHeight() const { return tile + caption; }
  int x0() const { return margin + label; }
  int y0() const { return margin + title + header; }
  int width() const { return x0() + columns * (cellWidth() + margin); }
  int height() const { return y0() + rows * (cellHeight() + margin); }
  int cellX(int c) const { return x0() + c * (cellWidth() + margin); }
  int cellY(int r) const { return y0() + r * (cellHeight() + margin); }
};

// Text in DejaVu Sans (the font Debian installs with fontconfig); false where there is no
// font: the labels are then only in figure.md.
bool drawText(oiio::Canvas* canvas, int x, int y, const std::string& s, int size) {
  return oiio::api().canvasText(canvas, x, y, s, size, 0.0f, 0.0f, 0.0f);
}

// Words joined into lines of at most `width` characters (a longer word stands alone).
std::vector<std::string> wrapWords(const std::string& text, std::size_t width) {
  std::vector<std::string> lines(1);
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    if (!lines.back().empty() && lines.back().size() + 1 + word.size() > width)
      lines.emplace_back();
    lines.back() += (lines.back().empty() ? "" : " ") + word;
    start = end + 1;
  }
  return lines;
}

// One image fitted into a tile x tile box at (x, y), letterboxed; false when it cannot be read.
bool pasteFitted(oiio::Canvas* canvas, const fs::path& file, int x, int y, int tile) {
  return oiio::api().canvasPaste(canvas, file.string(), x, y, tile);
}

std::string caption(const nlohmann::json& r) {
  using namespace report;
  std::string s;
  if (auto ms = frameMs(r)) s += formatSig(*ms) + " ms";
  if (auto e = number(find(r, {"error", "image", "rmse"}))) s += "  RMSE " + formatSig(*e, 2);
  if (auto f = number(find(r, {"error", "image", "flip", "mean"})))
    s += "  FLIP " + formatSig(*f, 2);
  return s;
}

// Writes dir/figure.png; returns its layout (figure.json "layout").
nlohmann::json composeGrid(const report::FigureGrid& g, const fs::path& dir) {
  Layout L;
  L.rows = static_cast<int>(g.rows.size());
  L.columns = static_cast<int>(g.columns.size());
  const oiio::Api& io = oiio::api();
  const std::unique_ptr<oiio::Canvas, void (*)(oiio::Canvas*)> owned(
      io.canvasCreate(L.width(), L.height()), io.canvasFree);
  oiio::Canvas* canvas = owned.get();
  bool labels = drawText(canvas, L.margin, L.margin + 22,
                         g.title + " (" + g.backend + "; each cell: ours | error heatmap)", 20);
  for (int c = 0; c < L.columns; ++c)
    labels &= drawText(canvas, L.cellX(c), L.margin + L.title + 18, g.columns[c], 16);
  for (int r = 0; r < L.rows; ++r) {
    int line = 0;
    for (const std::string& part : wrapWords(g.rows[r], 20))
      labels &= drawText(canvas, L.margin, L.cellY(r) + L.tile / 2 + 18 * line++, part, 14);
    for (int c = 0; c < L.columns; ++c) {
      const report::FigureCell& cell = g.cells[r][c];
      const int x = L.cellX(c), y = L.cellY(r);
      bool pasted = false;
      if (cell.result && cell.note.empty()) {
        const nlohmann::json* im = report::find(*cell.result, {"images"});
        const std::string image = im ? report::text(report::find(*im, {"image"})) : "";
        const std::string heat = im ? report::text(report::find(*im, {"heatmap"})) : "";
        pasted = !image.empty() && pasteFitted(canvas, dir / image, x, y, L.tile);
        if (!heat.empty()) pasteFitted(canvas, dir / heat, x + L.tile + L.gap, y, L.tile);
        labels &= drawText(canvas, x, y + L.tile + 15, caption(*cell.result), 13);
      }
      if (!pasted) {  // grey: the paper has no image here, or we have none
        io.canvasFill(canvas, x, x + L.cellWidth(), y, y + L.tile, 0.5f, 0.5f, 0.5f);
        labels &= drawText(canvas, x + 8, y + 24, cell.note.substr(0, 60), 13);
      }
    }
  }
  Image img(L.width(), L.height(), 3);
  io.canvasPixels(canvas, img.pixels.data());
  writeImage(img, (dir / "figure.png").string());
  return {{"width", L.width()}, {"height", L.height()},        {"tile", L.tile},
          {"gap", L.gap},       {"margin", L.margin},          {"x0", L.x0()},
          {"y0", L.y0()},       {"cell_width", L.cellWidth()}, {"cell_height", L.cellHeight()},
          {"labels", labels}};
}

std::string commandText(const FigureOptions& o, const std::string& out) {
  std::string runs;  // the run options given, as they are typed: " --min-reps 3"
  for (const std::string& a : runOptionArguments(o.rounds)) runs += " " + a;
  return "strandbench figure " + o.name + (o.small ? " --small" : "") + runs + " --backend " +
         o.backend + " --out " + out + (o.docs.empty() ? "" : " --docs " + o.docs);
}

// Each cell's banding measure against its reference, where both images are in `dir`.
void addBanding(report::FigureGrid& g, const fs::path& dir) {
  for (auto& row : g.cells)
    for (report::FigureCell& cell : row) {
      if (!cell.result || !cell.note.empty()) continue;
      const nlohmann::json* im = report::find(*cell.result, {"images"});
      const std::string image = im ? report::text(report::find(*im, {"image"})) : "";
      const std::string ref = im ? report::text(report::find(*im, {"reference"})) : "";
      if (image.empty() || ref.empty() || !fs::is_regular_file(dir / image) ||
          !fs::is_regular_file(dir / ref))
        continue;
      try {
        cell.banding =
            bandingMeasure(readImage((dir / image).string()), readImage((dir / ref).string()));
      } catch (const InputError&) {
        // sizes differ: no measure for this cell
      }
    }
}

// Every technique spec under `j` ("shadow", "oit", "shading" keys, their axes' arrays, the
// figure's cells): its family and name.
void techniqueSpecs(const nlohmann::json& j, const std::string& key,
                    std::set<std::pair<Family, std::string>>& out) {
  static const std::pair<const char*, Family> kFamilies[] = {
      {"shadow", Family::Shadow}, {"oit", Family::Transparency}, {"shading", Family::Shading}};
  if (j.is_string()) {
    for (const auto& [k, family] : kFamilies)
      if (key == k)
        out.emplace(family, j.get<std::string>().substr(0, j.get<std::string>().find(':')));
  } else if (j.is_array()) {
    for (const auto& v : j) techniqueSpecs(v, key, out);
  } else if (j.is_object()) {
    for (const auto& [k, v] : j.items()) techniqueSpecs(v, k, out);
  }
}

}  // namespace

std::vector<std::string> figureBackends(const std::string& backend) {
  std::vector<std::string> names = backendNames();
  if (backend == kBothBackends) return names;
  if (std::find(names.begin(), names.end(), backend) == names.end()) {
    names.push_back(kBothBackends);
    throw InputError("--backend " + backend + ": " + unknownNameMessage("backend", backend, names));
  }
  return {backend};
}

fs::path figuresDir() { return fs::path(SB_SOURCE_DIR) / "suites" / "figures"; }

fs::path modelsDir() {
  if (const char* e = std::getenv("SB_MODELS_DIR"); e && *e) return e;
  return (fs::path(SB_SOURCE_DIR) / ".." / "shared" / "models").lexically_normal();
}

std::vector<std::string> figureNames() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(figuresDir(), ec))
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

ojson figureSuite(const std::string& name, bool small, const std::string& backend) {
  const fs::path file = figureFile(name);
  const std::string where = "figure " + file.string();
  ojson doc = readJsonFile<ojson>(file);
  if (!doc.is_object()) throw InputError(where + ": not a JSON object");
  const std::vector<std::string> backends = figureBackends(backend);
  report::checkFigureBlock(nlohmann::json::parse(doc.dump()), where);
  if (const ojson* models = doc["figure"].contains("models") ? &doc["figure"]["models"] : nullptr) {
    for (const auto& m : *models) {
      const fs::path p = modelsDir() / m.get<std::string>();
      if (!fs::is_regular_file(p))
        throw InputError(where + ": needs the model " + p.string() +
                         ", which is missing (the models of ../shared/models; SB_MODELS_DIR "
                         "names another folder)");
    }
  }
  if (small) applySmall(doc, where);
  doc.erase("small");
  onBackends(doc, backends);
  for (const char* key : {"defaults", "presets", "groups"})
    if (doc.contains(key)) resolveModels(doc[key], modelsDir().string() + "/");
  return doc;
}

int runFigure(const FigureOptions& o) {
  const std::string name = figureName(o.name);
  const ojson doc = figureSuite(o.name, o.small, o.backend);
  if (!o.docs.empty()) {
    // A page the docs cite names the commit that ran; a tree with edits is not that commit.
    if (const std::string dirty = uncommittedCode(); !dirty.empty())
      throw InputError("figure " + name + " --docs: the tree has uncommitted changes (" + dirty +
                       " ...); commit them first: the docs cite only runs of a clean commit");
  }
  const std::string outText =
      o.out.empty() ? "figures/" + name + (o.small ? "-small" : "") + "-" + o.backend : o.out;
  const fs::path out = fs::path(outText).lexically_normal();
  if (fs::exists(out)) {
    const bool figureFolder =
        fs::is_directory(out) && (fs::is_empty(out) || fs::is_regular_file(out / "figure.json"));
    if (!figureFolder)
      throw InputError("--out " + outText +
                       ": exists and is not a figure folder (no figure.json); choose a new folder");
  }
  checkOutputFolder("--out", out.parent_path().empty() ? "." : out.parent_path().string());
  const fs::path parent = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  std::error_code ec;
  fs::create_directories(parent, ec);
  const fs::path tmp =
      parent / ("." + out.filename().string() + ".tmp-" + std::to_string(::getpid()));
  fs::remove_all(tmp, ec);
  if (!fs::create_directory(tmp, ec))
    throw InputError("--out " + outText + ": cannot create " + tmp.string() + " (" + ec.message() +
                     ")");
  try {
    const fs::path suiteFile = tmp / "figure-suite.json";
    writeFileAtomic(suiteFile, doc.dump(2) + "\n");
    SweepOptions so;
    so.suitePath = suiteFile.string();
    so.out = tmp.string();
    so.shownOut = out.string();  // tmp is renamed to it when the figure is done
    so.progressBar = o.progressBar;
    so.rounds = o.rounds;
    so.interleaveAcrossGroups = true;
    so.cases = o.cases;
    const int status = runSweep(so);
    // The sweep records the suite file it read; name the figure instead of the temporary file.
    auto sweepDoc = readJsonFile<ojson>(tmp / "sweep.json");
    sweepDoc["suite_file"] = figureFile(o.name).string() + (o.small ? " (--small)" : "");
    writeFileAtomic(tmp / "sweep.json", sweepDoc.dump(1) + "\n");
    writeSweepReport(tmp.string());

    const auto results = readJsonFile<nlohmann::json>(tmp / "results.json");
    const auto figure = nlohmann::json::parse(doc["figure"].dump());
    report::FigureGrid grid =
        report::buildFigureGrid(figure, results, name, figureBackends(o.backend));
    addBanding(grid, tmp);
    const nlohmann::json layout = composeGrid(grid, tmp);
    writeFileAtomic(tmp / "figure.json", report::figureJson(grid, layout).dump(1) + "\n");
    const std::string command = commandText(o, outText);
    writeFileAtomic(tmp / "figure.md",
                    report::renderFigureMarkdown(grid, results, "figure.png", command));
    if (!o.docs.empty()) {
      // The page the docs include: the same Markdown beside its own copy of the grid.
      const fs::path docs(o.docs);
      fs::create_directories(docs, ec);
      writeFileAtomic(docs / (name + ".md"),
                      report::renderFigureMarkdown(grid, results, name + ".png", command));
      fs::copy_file(tmp / "figure.png", docs / (name + ".png"),
                    fs::copy_options::overwrite_existing);
    }
    if (fs::exists(out)) fs::remove_all(out);
    fs::rename(tmp, out);
    std::cout << "wrote " << (out / "figure.png").string() << " (" << grid.rows.size() << " x "
              << grid.columns.size() << " cells), figure.md, figure.json and the sweep's reports"
              << (status ? "; some cases failed (their cells say why)" : "") << "\n";
    return status;
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
}

std::optional<double> FigurePaperRow::paperMs() const {
  if (!paper || *paper <= 0) return std::nullopt;
  if (unit == "fps") return 1000.0 / *paper;
  if (unit == "ms") return paper;
  return std::nullopt;
}

const FigurePaperRow& FigurePaperTable::row(const std::string& spec, bool oit) const {
  for (const FigurePaperRow& r : rows)
    if ((oit ? r.oit : r.shadow) == spec) return r;
  throw InputError("figure " + figure + ", table \"" + title + "\": no row with " +
                   (oit ? "oit " : "shadow ") + spec + " (suites/figures/" + figure + ".json)");
}

FigurePaperTable figurePaperTable(const std::string& name, std::size_t index) {
  const fs::path file = figureFile(name);
  const std::string where = "figure " + file.string();
  const ojson doc = readJsonFile<ojson>(file);
  if (!doc.contains("tables") || !doc["tables"].is_array() || index >= doc["tables"].size())
    throw InputError(where + ": has no paper table " + std::to_string(index + 1) + " (\"tables\")");
  const ojson& t = doc["tables"][index];
  FigurePaperTable out;
  out.figure = figureName(name);
  out.title = t.value("title", "");
  out.source = t.value("source", "");
  const ojson defaults = doc.value("defaults", ojson::object());
  const ojson groups = doc.value("groups", ojson::array());
  for (const ojson& r : t.value("rows", ojson::array())) {
    FigurePaperRow row;
    row.label = r.value("label", "");
    const std::string group = r.value("group", t.value("group", ""));
    const ojson* g = nullptr;
    for (const ojson& candidate : groups)
      if (candidate.value("name", "") == group) g = &candidate;
    if (!g)
      throw InputError(where + ": table \"" + out.title + "\", row \"" + row.label +
                       "\": group \"" + group + "\" is not a group of the suite");
    row.shadow = g->value("shadow", defaults.value("shadow", row.shadow));
    row.oit = g->value("oit", defaults.value("oit", row.oit));
    if (r.contains("paper") && r["paper"].is_number()) row.paper = r["paper"].get<double>();
    row.unit = r.value("paper_unit", t.value("paper_unit", row.unit));
    row.baseline = r.value("baseline", false);
    out.rows.push_back(std::move(row));
  }
  return out;
}

std::vector<std::string> figureDepends(const std::string& name) {
  const fs::path file = figuresDir() / (name + ".json");
  // A figure that is gone: its file, which git then lists as changed.
  if (!fs::is_regular_file(file)) return {"suites/figures/" + name + ".json"};
  std::set<std::pair<Family, std::string>> specs;
  techniqueSpecs(readJsonFile<nlohmann::json>(file), "", specs);
  std::set<std::string> out = {fs::relative(file, SB_SOURCE_DIR).generic_string(),
                               "harness/figure.cpp", "reports/figure_report.cpp",
                               // the floor every technique draws through
                               "render"};
  for (Family f : {Family::Shadow, Family::Transparency, Family::Shading}) {
    out.insert("techniques/" + defaultTechnique(f).folder);
    // The references every figure's errors are measured against.
    for (const TechniqueDescriptor* d : techniques(f))
      if (d->caps.exact) out.insert("techniques/" + d->folder);
  }
  for (const auto& [family, n] : specs)
    if (const TechniqueDescriptor* d = tryFindTechnique(family, n))
      out.insert("techniques/" + d->folder);
  return {out.begin(), out.end()};
}

}  // namespace sb
