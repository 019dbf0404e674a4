#include "harness/driver_ab.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "backends/driver_env.h"
#include "harness/expectations.h"
#include "harness/run_context.h"
#include "harness/run_options.h"
#include "imaging/flip.h"
#include "imaging/image.h"
#include "imaging/metrics.h"
#include "reports/files.h"
#include "reports/json_file.h"
#include "reports/stats.h"
#include "reports/svg_chart.h"

namespace sb {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

namespace {

std::string fmt(double v, int digits = 3) {
  if (!std::isfinite(v)) return "-";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

// The frame-time samples a result holds.
std::vector<double> frameSamples(const ojson& r) {
  std::vector<double> v;
  if (r.contains("frame_ms") && r["frame_ms"].contains("samples"))
    for (const auto& x : r["frame_ms"]["samples"]) v.push_back(x.get<double>());
  return v;
}

// Results of a sweep folder by case id.
std::map<std::string, ojson> resultsById(const fs::path& dir) {
  std::map<std::string, ojson> m;
  const ojson doc = readJsonFile<ojson>(dir / "results.json");
  for (const auto& r : doc["results"]) m[r["case"]["id"].get<std::string>()] = r;
  return m;
}

const char* kStyle =
    "body{font:13px sans-serif;margin:16px;max-width:1400px}"
    "table.sum{border-collapse:collapse}table.sum td,table.sum th{border:1px solid #ccc;"
    "padding:2px 6px;text-align:right}table.sum td:first-child{text-align:left}"
    ".case{border-top:1px solid #aaa;padding:8px 0}.imgs{display:flex;gap:8px;flex-wrap:wrap}"
    ".imgs figure{margin:0}.imgs img{width:192px;image-rendering:pixelated;border:1px solid #888}"
    "figcaption{font-size:11px;color:#444}.same{color:#777}.changed{color:#b00}"
    "button{font-size:12px}";

}  // namespace

int writeDriverAbPage(const std::string& outText) {
  const fs::path out = outText;
  if (!fs::is_regular_file(out / "ab.json"))
    throw InputError(outText + ": not a driver A/B folder (no ab.json)");
  ojson ab = readJsonFile<ojson>(out / "ab.json");
  const std::string a = ab["a"]["name"], b = ab["b"]["name"];
  const fs::path da = out / "a", db = out / "b";
  for (const fs::path& d : {da, db})
    if (!fs::is_regular_file(d / "results.json"))
      throw InputError(d.string() + ": no results.json (the sweep did not finish; --resume)");
  loadImageModule();
  const auto ra = resultsById(da), rb = resultsById(db);
  fs::create_directories(out / "ab");
  ojson pairs = ojson::array();
  for (const auto& [id, x] : ra) {
    const auto it = rb.find(id);
    if (it == rb.end()) continue;
    const ojson& y = it->second;
    ojson p = {{"id", id}, {"a", ojson::object()}, {"b", ojson::object()}};
    for (const auto& [side, r] : {std::pair{"a", &x}, std::pair{"b", &y}}) {
      p[side]["driver"] = r->value("driver", "");
      if (r->contains("failed")) p[side]["failed"] = (*r)["failed"]["reason"];
      if (r->contains("images") && (*r)["images"].contains("image"))
        p[side]["image"] = std::string(side) + "/" + (*r)["images"]["image"].get<std::string>();
      if (r->contains("frame_ms")) p[side]["frame_ms"] = (*r)["frame_ms"]["median"];
      if (r->contains("measurement"))
        p[side]["median_ci95_ms"] = (*r)["measurement"]["median_ci95_ms"];
      if (r->contains("frame_work")) p[side]["work"] = (*r)["frame_work"];
      if (r->contains("error") && (*r)["error"].contains("image"))
        p[side]["rmse_vs_reference"] = (*r)["error"]["image"]["rmse"];
    }
    // The change between the two drivers' images.
    if (p["a"].contains("image") && p["b"].contains("image")) {
      const Image ia = readImage((out / p["a"]["image"].get<std::string>()).string());
      const Image ib = readImage((out / p["b"]["image"].get<std::string>()).string());
      if (ia.width == ib.width && ia.height == ib.height) {
        const ImageError e = compareImages(ib, ia, 1.0 / 255.0, 3);
        const FlipResult f = computeFlip(ib, ia);
        const std::string stem =
            "ab/" + fs::path(p["a"]["image"].get<std::string>()).stem().string();
        const double scale = e.maxAbs > 0 ? e.maxAbs : 1.0;
        writeImage(diffHeatmap(ib, ia, scale), (out / (stem + ".heatmap.png")).string());
        writeImage(flipErrorImage(f), (out / (stem + ".flip.png")).string());
        p["change"] = {{"max_abs", e.maxAbs},
                       {"rmse", e.rmse},
                       {"pixels_over", e.pixelsOver},
                       {"flip_mean", f.mean},
                       {"heatmap", stem + ".heatmap.png"},
                       {"heatmap_scale", scale},
                       {"flip", stem + ".flip.png"}};
      }
    }
    // Frame time: B over A with a 95% interval; the sweeps ran one after the other, so the
    // samples are not paired and a slow spell of the machine shows as a difference.
    const std::vector<double> sa = frameSamples(x), sb = frameSamples(y);
    if (sa.size() >= 2 && sb.size() >= 2) {
      const Interval ratio = bootstrapRatio(sb, sa, /*paired=*/false);
      const std::string v = orderingVerdict(ratio, 1.0, /*claimBelow=*/true);
      p["time_ratio_b_over_a"] = {{"estimate", ratio.estimate},
                                  {"ci95", {ratio.low, ratio.high}},
                                  {"verdict", v == "holds"   ? "b faster"
                                              : v == "fails" ? "b slower"
                                                             : "undecided"}};
    }
    pairs.push_back(p);
  }
  // Largest change first: mean FLIP, then max abs; pairs without images last.
  auto key = [](const ojson& p) {
    return p.contains("change") ? std::pair{p["change"]["flip_mean"].get<double>(),
                                            p["change"]["max_abs"].get<double>()}
                                : std::pair{-1.0, -1.0};
  };
  std::stable_sort(pairs.begin(), pairs.end(),
                   [&](const ojson& l, const ojson& r) { return key(l) > key(r); });
  ab["pairs"] = pairs;
  int changed = 0;
  for (const auto& p : pairs)
    if (p.contains("change") && p["change"]["max_abs"].get<double>() > 0) ++changed;
  ab["changed"] = changed;
  writeFileAtomic(out / "ab.json", ab.dump(1) + "\n");

  // The page.
  std::ostringstream h;
  h << "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>driver A/B: " << htmlEscape(a)
    << " against " << htmlEscape(b) << "</title><style>" << kStyle
    << "</style></head><body>\n<h1>Driver A/B: " << htmlEscape(a) << " (A) against "
    << htmlEscape(b) << " (B)</h1>\n<p>Suite <code>" << htmlEscape(ab.value("suite", ""))
    << "</code>; A: " << htmlEscape(ab["a"].value("version", a))
    << "; B: " << htmlEscape(ab["b"].value("version", b)) << ". " << pairs.size() << " cases, "
    << changed
    << " with a changed image (8-bit PNGs compared), sorted by the change (mean FLIP of B "
       "against A). Times: medians with 95% intervals; the two sweeps ran one after the "
       "other, so their ratio's interval is unpaired and a verdict needs it to exclude 1. "
       "Click an image to toggle between the drivers.</p>\n";
  h << "<table class=\"sum\"><tr><th>case</th><th>FLIP B vs A</th><th>max abs</th><th>pixels "
       "over 1/255</th><th>RMSE vs ref A</th><th>RMSE vs ref B</th><th>ms A</th><th>ms "
       "B</th><th>B/A [95%]</th><th>time</th><th>work</th></tr>\n";
  auto workText = [](const ojson& p) -> std::string {
    if (!p["a"].contains("work") || !p["b"].contains("work")) return "-";
    if (p["a"]["work"] == p["b"]["work"]) return "same";
    std::string s;
    for (const auto& [k, v] : p["a"]["work"].items())
      if (p["b"]["work"].contains(k) && p["b"]["work"][k] != v)
        s += (s.empty() ? "" : ", ") + k + " " + v.dump() + "&rarr;" + p["b"]["work"][k].dump();
    return s;
  };
  auto num = [](const ojson& o, const char* k) {
    return o.contains(k) && o[k].is_number() ? fmt(o[k].get<double>()) : std::string("-");
  };
  int index = 0;
  for (const auto& p : pairs) {
    const bool moved = p.contains("change") && p["change"]["max_abs"].get<double>() > 0;
    h << "<tr><td><a href=\"#c" << index++ << "\">" << htmlEscape(p["id"]) << "</a></td>";
    if (p.contains("change"))
      h << "<td class=\"" << (moved ? "changed" : "same") << "\">"
        << fmt(p["change"]["flip_mean"].get<double>()) << "</td><td>"
        << fmt(p["change"]["max_abs"].get<double>()) << "</td><td>"
        << p["change"]["pixels_over"].get<long long>() << "</td>";
    else
      h << "<td>-</td><td>-</td><td>-</td>";
    h << "<td>" << num(p["a"], "rmse_vs_reference") << "</td><td>"
      << num(p["b"], "rmse_vs_reference") << "</td><td>" << num(p["a"], "frame_ms") << "</td><td>"
      << num(p["b"], "frame_ms") << "</td>";
    if (p.contains("time_ratio_b_over_a")) {
      const ojson& t = p["time_ratio_b_over_a"];
      h << "<td>" << fmt(t["estimate"].get<double>()) << " [" << fmt(t["ci95"][0].get<double>())
        << ", " << fmt(t["ci95"][1].get<double>()) << "]</td><td>"
        << t["verdict"].get<std::string>() << "</td>";
    } else {
      h << "<td>-</td><td>-</td>";
    }
    h << "<td>" << workText(p) << "</td></tr>\n";
  }
  h << "</table>\n";
  index = 0;
  for (const auto& p : pairs) {
    // A case whose images are the same is folded: the page opens on what changed.
    const bool moved = !p.contains("change") || p["change"]["max_abs"].get<double>() > 0;
    h << "<details class=\"case\" id=\"c" << index++ << "\"" << (moved ? " open" : "")
      << "><summary><b>" << htmlEscape(p["id"]) << "</b>" << (moved ? "" : ": the same image")
      << "</summary>";
    for (const char* side : {"a", "b"})
      if (p[side].contains("failed"))
        h << "<p class=\"changed\">" << (side[0] == 'a' ? "A" : "B")
          << " failed: " << htmlEscape(p[side]["failed"]) << "</p>";
    h << "<div class=\"imgs\">";
    if (p["a"].contains("image") && p["b"].contains("image")) {
      const std::string ia = htmlEscape(p["a"]["image"]), ib = htmlEscape(p["b"]["image"]);
      h << "<figure><img class=\"toggle\" src=\"" << ia << "\" data-a=\"" << ia << "\" data-b=\""
        << ib << "\" alt=\"A/B toggle\"><figcaption><span class=\"which\">A: " << htmlEscape(a)
        << "</span> (click: toggle)</figcaption></figure>";
      h << "<figure><img src=\"" << ia << "\" alt=\"A\"><figcaption>A: " << htmlEscape(a)
        << "</figcaption></figure><figure><img src=\"" << ib
        << "\" alt=\"B\"><figcaption>B: " << htmlEscape(b) << "</figcaption></figure>";
    }
    if (p.contains("change"))
      h << "<figure><img src=\"" << htmlEscape(p["change"]["heatmap"]) << "\" alt=\"heatmap\">"
        << "<figcaption>|B - A|, full scale " << fmt(p["change"]["heatmap_scale"].get<double>())
        << "</figcaption></figure><figure><img src=\"" << htmlEscape(p["change"]["flip"])
        << "\" alt=\"FLIP\"><figcaption>FLIP, B against A (mean "
        << fmt(p["change"]["flip_mean"].get<double>()) << ")</figcaption></figure>";
    h << "</div></details>\n";
  }
  h << "<script>\nfor (const img of document.querySelectorAll('img.toggle')) {\n"
       "  img.addEventListener('click', () => {\n"
       "    const toB = img.getAttribute('src') === img.dataset.a;\n"
       "    img.src = toB ? img.dataset.b : img.dataset.a;\n"
       "    img.parentElement.querySelector('.which').textContent = toB ? 'B: "
    << htmlEscape(b) << "' : 'A: " << htmlEscape(a) << "';\n  });\n}\n</script>\n</body></html>\n";
  writeFileAtomic(out / "ab.html", h.str());
  return static_cast<int>(pairs.size());
}

int runDriverAb(const DriverAbOptions& o) {
  if (o.b.empty()) throw InputError("--b DRIVER is required (the driver compared with --a)");
  checkDriver(o.a);
  checkDriver(o.b);
  if (driverKey(o.a) == driverKey(o.b))
    throw InputError("--a and --b name the same driver (" + driverKey(o.a) + ")");
  if (!fs::is_regular_file(o.suitePath))
    throw InputError("suite " + o.suitePath + ": no such file");
  const fs::path out = o.out;
  if (fs::exists(out / "ab.json") && !o.resume)
    throw InputError("--out " + o.out +
                     " already holds a driver A/B: add --resume, or choose "
                     "another folder");
  fs::create_directories(out);
  ojson ab = {{"suite", o.suitePath},
              {"filter", o.filter},
              {"a", {{"name", driverKey(o.a)}, {"driver", o.a}}},
              {"b", {{"name", driverKey(o.b)}, {"driver", o.b}}},
              {"context", runContext()}};
  writeFileAtomic(out / "ab.json", ab.dump(1) + "\n");
  int status = 0;
  for (const auto& [side, driver] : {std::pair{"a", o.a}, std::pair{"b", o.b}}) {
    std::cout << "driver A/B: " << side << " = " << driver << "\n";
    std::vector<std::string> args = {"sweep", o.suitePath, "--driver",
                                     driver,  "--out",     (out / side).string()};
    if (!o.filter.empty()) args.insert(args.end(), {"--filter", o.filter});
    if (o.resume && fs::exists(out / side / "sweep.json")) args.push_back("--resume");
    const int s = childStatus(runSelfOnDriver(driver, args), "driver A/B: the sweep on " + driver);
    if (s != 0) status = 1;
    // The driver's version string, from its first result.
    if (fs::is_regular_file(out / side / "results.json")) {
      const ojson doc = readJsonFile<ojson>(out / side / "results.json");
      if (!doc["results"].empty()) ab[side]["version"] = doc["results"][0].value("driver", "");
    }
  }
  writeFileAtomic(out / "ab.json", ab.dump(1) + "\n");
  const int n = writeDriverAbPage(o.out);
  std::cout << "wrote " << (out / "ab.html").string() << " (" << n << " cases paired)\n";
  return status;
}

}  // namespace sb
