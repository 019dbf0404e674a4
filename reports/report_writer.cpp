// results.csv and report.md, and writeReports (report.html: reports/report_html.cpp).
#include "reports/report_writer.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "base/errors.h"
#include "reports/files.h"
#include "reports/report_data.h"

namespace sb {

namespace report {

namespace {

// RFC 4180: quote a field holding a comma, quote or line break (specs hold commas).
std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos && (s.empty() || s.front() != ' ')) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

// Markdown inline text: characters that would start markup, or end a table
// cell, are backslash-escaped; line breaks become spaces.
std::string md(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '\n' || c == '\r') {
      out += ' ';
      continue;
    }
    if (std::string_view("\\`*_[]<>|#").find(c) != std::string_view::npos) out += '\\';
    out += c;
  }
  return out;
}

void mdTable(std::ostream& o, const Table& t) {
  if (t.header.empty()) return;
  o << "|";
  for (const std::string& h : t.header) o << " " << md(h) << " |";
  o << "\n|";
  for (std::size_t c = 0; c < t.header.size(); ++c) {
    bool number = false;
    for (const auto& row : t.rows) number |= c < row.size() && row[c].number;
    o << (number ? " ---: |" : " --- |");
  }
  o << "\n";
  for (const auto& row : t.rows) {
    o << "|";
    for (const Cell& cell : row) o << " " << md(cell.text) << " |";
    o << "\n";
  }
  o << "\n";
}

std::string renderCsv(const ReportData& d) {
  std::ostringstream o;
  o << "case_id,group,backend,scene,segments,shadow,oit,size,frame_ms_median,frame_ms_min,"
       "frame_ms_max,frame_ms_stddev,memory_total_bytes,memory_shadow_bytes,memory_oit_bytes,"
       "image_rmse,image_psnr,image_ssim,image_flip_mean,visibility_rmse,visibility_max,"
       "depth_complexity_eye_max,depth_complexity_light_max,own_technique,own_image_rmse,"
       "own_image_flip_mean,own_visibility_rmse,animation,animation_frames,animation_degrees,"
       "flicker_image,flicker_visibility,failed";
  // The frame's work counters last, so the columns before them keep their places.
  for (const WorkColumn& c : kWorkColumns) o << "," << c.key;
  // Each further reference's error and cost after them (error.aa: aa_image_rmse, ...),
  // only when a result has one.
  const std::vector<std::string> more = moreReferenceNames(d.results);
  const std::vector<std::pair<std::string, std::vector<std::string_view>>> moreColumns = {
      {"image_rmse", {"rmse"}},
      {"image_psnr", {"psnr"}},
      {"image_ssim", {"ssim"}},
      {"image_flip_mean", {"flip", "mean"}},
      {"reference_spec", {"reference", "spec"}},
      {"reference_wall_ms", {"reference", "wall_ms"}},
      {"reference_bytes", {"reference", "bytes"}}};
  for (const std::string& name : more)
    for (const auto& [column, path] : moreColumns) o << "," << name << "_" << column;
  o << "\n";
  for (const json* r : d.results) {
    // Numbers in full precision; null (NaN, Inf) and missing values as empty cells.
    auto n = [&](std::initializer_list<std::string_view> path) {
      const json* v = find(*r, path);
      return v && v->is_number() ? text(v) : std::string();
    };
    const std::vector<std::string> fields = {
        text(find(*r, {"case", "id"})),
        groupOf(*r),
        backendOf(*r),
        text(find(*r, {"scene", "spec"})),
        n({"scene", "segments"}),
        text(find(*r, {"shadow"})),
        text(find(*r, {"oit"})),
        sizeOf(*r),
        n({"frame_ms", "median"}),
        n({"frame_ms", "min"}),
        n({"frame_ms", "max"}),
        n({"frame_ms", "stddev"}),
        n({"memory", "total_bytes"}),
        n({"memory", "shadow_bytes"}),
        n({"memory", "oit_bytes"}),
        n({"error", "image", "rmse"}),
        n({"error", "image", "psnr"}),
        n({"error", "image", "ssim"}),
        n({"error", "image", "flip", "mean"}),
        n({"error", "visibility", "rmse"}),
        n({"error", "visibility", "max"}),
        n({"depth_complexity", "eye", "max"}),
        n({"depth_complexity", "light", "max"}),
        text(find(*r, {"error", "own", "technique"})),
        n({"error", "own", "image", "rmse"}),
        n({"error", "own", "image", "flip", "mean"}),
        n({"error", "own", "visibility", "rmse"}),
        text(find(*r, {"animation", "kind"})),
        n({"animation", "frames"}),
        n({"animation", "degrees"}),
        n({"animation", "flicker", "image"}),
        n({"animation", "flicker", "visibility"}),
        failureOf(*r),  // empty for a case that ran
    };
    std::vector<std::string> row = fields;
    for (const WorkColumn& c : kWorkColumns) row.push_back(n({"frame_work", c.key}));
    for (const std::string& name : more) {
      const json* e = find(*r, {"error", name});
      for (const auto& [column, path] : moreColumns) {
        const json* v = nullptr;
        if (e) {
          v = e;
          for (std::string_view k : path) v = v && v->is_object() ? find(*v, {k}) : nullptr;
        }
        row.push_back(!v ? std::string() : v->is_number() || v->is_string() ? text(v) : "");
      }
    }
    for (std::size_t i = 0; i < row.size(); ++i) o << (i ? "," : "") << csvField(row[i]);
    o << "\n";
  }
  return o.str();
}

std::string renderPassesCsv(const ReportData& d) {
  std::ostringstream o;
  o << "case_id,backend,technique,pass,executions,ms_median";
  for (const WorkColumn& c : kWorkColumns) o << "," << c.key;
  o << "\n";
  const bool nameOit = anyTransparency(d.results), nameShadow = anyShadow(d.results);
  for (const json* r : d.results) {
    const json* passes = find(*r, {"passes"});
    if (!passes || !passes->is_array()) continue;
    for (const json& p : *passes) {
      auto n = [](const json* v) { return v && v->is_number() ? text(v) : std::string(); };
      std::vector<std::string> row = {text(find(*r, {"case", "id"})),
                                      backendOf(*r),
                                      shortTechniqueOf(*r, nameOit, nameShadow),
                                      text(find(p, {"name"})),
                                      n(find(p, {"executions"})),
                                      n(find(p, {"ms", "median"}))};
      for (const WorkColumn& c : kWorkColumns) row.push_back(n(find(p, {"work", c.key})));
      for (std::size_t i = 0; i < row.size(); ++i) o << (i ? "," : "") << csvField(row[i]);
      o << "\n";
    }
  }
  return o.str();
}

std::string costModelTitle(const CostModel& m) {
  return m.backend + " on " + (m.device.empty() ? "(unnamed device)" : m.device);
}

std::string costModelSummary(const CostModel& m) {
  if (!m.fitted) return m.note;
  const std::size_t out = m.cases.size() - static_cast<std::size_t>(m.fitCases);
  return "R² = " + formatSig(*m.r2, 3) + " over the " + std::to_string(m.fitCases) +
         " cases in the fit" +
         (out ? "; " + std::to_string(out) + " marked inefficient left out (R² over all " +
                    std::to_string(m.cases.size()) + ": " + formatSig(m.r2All.value_or(NAN), 3) +
                    ")"
              : "") +
         (m.note.empty() ? "" : "; " + m.note) + ".";
}

std::string renderMarkdown(const ReportData& d) {
  std::ostringstream o;
  o << "# " << md(d.title) << "\n\n";
  if (!d.description.empty()) o << md(d.description) << "\n\n";

  o << "## Context\n\n";
  for (const auto& [label, value] : d.context) o << "- " << md(label) << ": " << md(value) << "\n";
  o << "\n";
  if (!d.devices.rows.empty()) mdTable(o, d.devices);

  if (!d.paperTables.empty()) {
    o << "## Paper tables\n\n";
    for (const PaperTable& t : d.paperTables) {
      o << "### " << md(t.title) << "\n\n" << md(t.about) << "\n\n";
      mdTable(o, t.table);
      for (const std::string& n : t.notes) o << "- Note: " << md(n) << "\n";
      if (!t.notes.empty()) o << "\n";
    }
  }

  o << "## Groups\n\n";
  if (d.groups.empty()) o << "No results.\n\n";
  for (const Group& g : d.groups) {
    o << "### " << md(g.name.empty() ? "(no group)" : g.name) << "\n\n";
    if (!g.description.empty()) o << md(g.description) << "\n\n";
    if (g.results.empty())
      o << "No results.\n\n";
    else
      mdTable(o, g.table);
  }

  if (std::any_of(d.groups.begin(), d.groups.end(),
                  [](const Group& g) { return !g.passes.rows.empty(); })) {
    o << "## Passes: time and work\n\n" << kPassesAbout << "\n\n";
    for (const Group& g : d.groups) {
      if (g.passes.rows.empty()) continue;
      o << "### " << md(g.name.empty() ? "(no group)" : g.name) << "\n\n";
      mdTable(o, g.passes);
    }
  }

  if (!d.costModels.empty()) {
    o << "## Cost model\n\n" << kCostModelAbout << "\n\n";
    for (const CostModel& m : d.costModels) {
      o << "### " << md(costModelTitle(m)) << "\n\n" << md(costModelSummary(m)) << "\n\n";
      if (m.fitted) mdTable(o, costTermsTable(m));
      if (!m.cases.empty()) mdTable(o, costCasesTable(m));
    }
  }

  if (!d.failures.empty()) {
    o << "## Failed cases\n\n";
    for (const Warning& f : d.failures) o << "- " << md(f.caseId) << ": " << md(f.message) << "\n";
    o << "\n";
  }

  if (!d.budgets.empty()) {
    o << "## Which technique within which budget\n\n"
         "Per scene, size and backend, from the Pareto frontiers of error against median frame "
         "time: for each budget, the most accurate technique that fits it.\n\n";
    for (const BudgetTable& b : d.budgets) {
      o << "### " << md(b.key) << "\n\n";
      mdTable(o, b.table);
    }
  }

  if (!d.animationTable.rows.empty()) {
    o << "## Error under animation\n\n"
         "Flicker: the mean over frames and pixels of |(T_t - T_{t-1}) - (R_t - R_{t-1})|, the "
         "technique's frame-to-frame change that the reference does not have.\n\n";
    mdTable(o, d.animationTable);
  }

  o << "## Warnings\n\n";
  if (d.warnings.empty()) o << "None.\n";
  for (const Warning& w : d.warnings) o << "- " << md(w.caseId) << ": " << md(w.message) << "\n";
  return o.str();
}

}  // namespace report

void writeReports(const nlohmann::json& results, const std::filesystem::path& dir) {
  if (!std::filesystem::is_directory(dir))
    throw InputError("report folder " + dir.string() + " does not exist or is not a folder");
  // Everything is rendered before the first file is written, so a document that
  // cannot be rendered leaves the folder as it was.
  const report::ReportData data = report::buildReport(results);
  const std::string csv = report::renderCsv(data);
  const std::string markdown = report::renderMarkdown(data);
  const std::string html = report::renderHtml(data, dir);
  const std::string passes = report::renderPassesCsv(data);
  const std::string costModel = report::costModelsJson(data.costModels).dump(1) + "\n";
  writeFileAtomic(dir / "results.csv", csv);
  writeFileAtomic(dir / "passes.csv", passes);
  writeFileAtomic(dir / "cost_model.json", costModel);
  writeFileAtomic(dir / "report.md", markdown);
  writeFileAtomic(dir / "report.html", html);
}

}  // namespace sb
