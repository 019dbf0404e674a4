// The results store, the docs' marked blocks and the loose-number check (reports/docs_store.h).
#include "reports/docs_store.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "base/errors.h"
#include "reports/figure_report.h"
#include "reports/files.h"
#include "reports/json_file.h"

namespace sb::docs {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

// "a\nb" or ["a", "b"] (a template kept readable in JSON as one string per line).
std::string joinedText(const json& j, const std::string& where) {
  if (j.is_string()) return j.get<std::string>();
  if (!j.is_array()) throw InputError(where + ": a template is a string or an array of lines");
  std::string out;
  for (const auto& l : j) {
    if (!l.is_string()) throw InputError(where + ": a template line is not a string");
    out += l.get<std::string>() + "\n";
  }
  return out;
}

std::string trim(std::string s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  size_t i = 0;
  while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
  return s.substr(i);
}

// ---- templates ----

const json* lookup(const std::string& path, const std::vector<const json*>& stack) {
  if (path == ".") return stack.back();
  std::vector<std::string> keys;
  std::istringstream in(path);
  for (std::string k; std::getline(in, k, '.');) keys.push_back(k);
  for (auto it = stack.rbegin(); it != stack.rend(); ++it) {
    if (!(*it)->is_object() || !(*it)->contains(keys[0])) continue;
    const json* j = &(**it)[keys[0]];
    for (size_t i = 1; i < keys.size(); ++i) {
      if (j->is_object() && j->contains(keys[i]))
        j = &(*j)[keys[i]];
      else if (j->is_array() && !keys[i].empty() &&
               keys[i].find_first_not_of("0123456789") == std::string::npos &&
               std::stoul(keys[i]) < j->size())
        j = &(*j)[std::stoul(keys[i])];
      else
        return nullptr;
    }
    return j;
  }
  return nullptr;
}

std::string thousands(long long v) {
  std::string digits = std::to_string(v < 0 ? -v : v), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return (v < 0 ? "-" : "") + out;
}

std::string formatValue(const json& v, const std::string& filter, const std::string& format,
                        const std::string& where) {
  if (v.is_null()) return "-";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
  if (!v.is_number()) throw InputError(where + ": not a number or text");
  double x = v.get<double>();
  if (filter == "mib")
    x /= 1048576.0;
  else if (filter == "kib")
    x /= 1024.0;
  else if (filter == "s")
    x /= 1000.0;
  else if (filter == "pct")
    x *= 100.0;
  else if (!filter.empty())
    throw InputError(where + ": unknown filter '" + filter + "' (mib, kib, s, pct)");
  char buf[64];
  if (format.empty()) {
    if (v.is_number_integer() && filter.empty()) return v.dump();
    std::snprintf(buf, sizeof buf, "%.4g", x);
  } else if (format == "d") {
    std::snprintf(buf, sizeof buf, "%lld", std::llround(x));
  } else if (format == ",d") {
    return thousands(std::llround(x));
  } else if (format.size() >= 3 && format[0] == '.' &&
             (format.back() == 'f' || format.back() == 'e')) {
    const std::string digits = format.substr(1, format.size() - 2);
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos)
      throw InputError(where + ": bad format '" + format + "' (.Nf, .Ne, d, ,d)");
    const std::string f = "%." + digits + format.back();
    std::snprintf(buf, sizeof buf, f.c_str(), x);
  } else {
    throw InputError(where + ": bad format '" + format + "' (.Nf, .Ne, d, ,d)");
  }
  return buf;
}

void renderRange(const std::string& t, size_t begin, size_t end, std::vector<const json*>& stack,
                 const std::string& where, std::string& out) {
  size_t pos = begin;
  while (pos < end) {
    const size_t open = t.find("{{", pos);
    if (open == std::string::npos || open >= end) {
      out.append(t, pos, end - pos);
      return;
    }
    out.append(t, pos, open - pos);
    const size_t close = t.find("}}", open);
    if (close == std::string::npos || close >= end) throw InputError(where + ": '{{' without '}}'");
    const std::string tag = trim(t.substr(open + 2, close - open - 2));
    pos = close + 2;
    if (tag.empty()) throw InputError(where + ": empty {{}}");
    if (tag[0] == '/') throw InputError(where + ": {{" + tag + "}} closes no section");
    if (tag[0] != '#') {
      std::string path = tag, filter, format;
      if (auto c = path.find(':'); c != std::string::npos) {
        format = path.substr(c + 1);
        path.resize(c);
      }
      if (auto b = path.find('|'); b != std::string::npos) {
        filter = path.substr(b + 1);
        path.resize(b);
      }
      const json* v = lookup(path, stack);
      if (!v) throw InputError(where + ": no value '" + path + "' in the stored results");
      out += formatValue(*v, filter, format, where + " {{" + tag + "}}");
      continue;
    }
    // A section: find its own {{/name}}, past nested sections of the same name.
    const std::string name = tag.substr(1), openTag = "{{#" + name + "}}",
                      closeTag = "{{/" + name + "}}";
    size_t depth = 1, scan = pos, bodyEnd = std::string::npos;
    while (depth > 0) {
      const size_t nextOpen = t.find(openTag, scan), nextClose = t.find(closeTag, scan);
      if (nextClose == std::string::npos || nextClose >= end)
        throw InputError(where + ": {{#" + name + "}} without {{/" + name + "}}");
      if (nextOpen < nextClose) {
        ++depth;
        scan = nextOpen + openTag.size();
      } else {
        --depth;
        bodyEnd = nextClose;
        scan = nextClose + closeTag.size();
      }
    }
    const json* v = lookup(name, stack);
    if (v && v->is_array()) {
      for (const auto& e : *v) {
        stack.push_back(&e);
        renderRange(t, pos, bodyEnd, stack, where, out);
        stack.pop_back();
      }
    } else if (v && !v->is_null() && !(v->is_boolean() && !v->get<bool>())) {
      stack.push_back(v);
      renderRange(t, pos, bodyEnd, stack, where, out);
      stack.pop_back();
    }
    pos = scan;
  }
}

std::string metaText(const json& meta, const char* key) {
  if (!meta.contains(key) || meta[key].is_null()) return "not recorded";
  const json& v = meta[key];
  if (v.is_string()) return v.get<std::string>();
  if (v.is_object() && v.contains("1min"))  // harness/run_context.h's loadAverage()
    return formatValue(v["1min"], "", ".2f", key) + " " + formatValue(v["5min"], "", ".2f", key) +
           " " + formatValue(v["15min"], "", ".2f", key);
  return v.dump();
}

// Lines inside a fenced code block (and the fences): a marker there is an example.
std::vector<bool> fencedLines(const std::vector<std::string>& lines) {
  std::vector<bool> out(lines.size(), false);
  bool in = false;
  for (size_t i = 0; i < lines.size(); ++i) {
    const bool fence = trim(lines[i]).rfind("```", 0) == 0;
    out[i] = in || fence;
    if (fence) in = !in;
  }
  return out;
}

const std::regex kBegin(R"(^\s*<!--\s*([A-Za-z0-9_./-]+):begin\b.*)");
const std::regex kEnd(R"(^\s*<!--\s*([A-Za-z0-9_./-]+):end\b.*)");

}  // namespace

std::string renderTemplate(const std::string& tmpl, const json& data, const std::string& where) {
  std::vector<const json*> stack{&data};
  std::string out;
  renderRange(tmpl, 0, tmpl.size(), stack, where, out);
  return out;
}

StoredRun loadRun(const fs::path& store, const std::string& name) {
  const fs::path dir = store / name;
  if (!fs::is_directory(dir))
    throw InputError(dir.string() +
                     ": no such stored run (docs/measured-pages.md says how one "
                     "is recorded)");
  StoredRun r;
  r.name = name;
  r.meta = readJsonFile(dir / "meta.json");
  r.results = readJsonFile(dir / "results.json");
  r.blocks = readJsonFile(dir / "blocks.json");
  const std::string m = (dir / "meta.json").string();
  for (const char* k : {"command", "commit", "date"})
    if (!r.meta.contains(k) || !r.meta[k].is_string() || r.meta[k].get<std::string>().empty())
      throw InputError(m + ": '" + k + "' missing");
  if (r.meta.value("dirty", false))
    throw InputError(m +
                     ": recorded on a tree with uncommitted changes; the docs cite only "
                     "runs of a clean commit");
  if (!r.blocks.contains("blocks") || !r.blocks["blocks"].is_object())
    throw InputError((dir / "blocks.json").string() + ": 'blocks' missing");
  return r;
}

std::vector<std::string> blockDepends(const StoredRun& run, const std::string& block) {
  std::vector<std::string> out;
  auto add = [&](const json& j) {
    if (!j.is_array()) return;
    for (const auto& p : j)
      if (p.is_string() && std::find(out.begin(), out.end(), p.get<std::string>()) == out.end())
        out.push_back(p.get<std::string>());
  };
  add(run.blocks.value("depends", json::array()));
  if (run.blocks["blocks"].contains(block))
    add(run.blocks["blocks"][block].value("depends", json::array()));
  return out;
}

std::string renderBlock(const StoredRun& run, const std::string& block, const fs::path& page) {
  const std::string where = "docs/results/" + run.name + "/blocks.json: block '" + block + "'";
  if (!run.blocks["blocks"].contains(block)) throw InputError(where + " is not there");
  const json& spec = run.blocks["blocks"][block];
  const json& meta = run.meta;
  const std::string commit = meta["commit"].get<std::string>();
  std::string machine = "machine not recorded";
  if (meta.contains("machine") && meta["machine"].is_object()) {
    const json& m = meta["machine"];
    auto part = [&](const char* k, const std::string& format) {
      return m.contains(k) && !m[k].is_null() ? formatValue(m[k], "", format, where) : "?";
    };
    machine = (m.contains("cpu") && m["cpu"].is_string() ? m["cpu"].get<std::string>()
                                                         : std::string("CPU not recorded")) +
              " (" + part("cores", "") + " cores, " + part("memory_gib", ".0f") + " GiB)";
  }
  const fs::path runDir = fs::path("docs/results") / run.name;
  const std::string link = runDir.lexically_relative(page.parent_path()).generic_string();
  std::string deps;
  for (const auto& d : blockDepends(run, block)) {
    deps += deps.empty() ? "`" : ", `";
    deps += d;
    deps += '`';
  }
  std::string out = "Measured by `" + meta["command"].get<std::string>() + "` on commit `";
  out += commit.substr(0, 7);
  out += "`, " + meta["date"].get<std::string>() + ", " + machine;
  out += ", driver " + metaText(meta, "driver");
  out += ", load average " + metaText(meta, "load_before");
  out += " before and " + metaText(meta, "load_after");
  out += " after; stored in [" + runDir.generic_string() + "](" + link + ")";
  if (!deps.empty()) out += ", depends on " + deps;
  out += '.';
  if (meta.contains("note")) {
    out += ' ';
    out += metaText(meta, "note");
  }
  out += '\n';
  json data = run.results;
  if (data.is_object()) data["meta"] = meta;
  const std::string body =
      renderTemplate(joinedText(spec.value("template", json("")), where), data, where);
  if (!body.empty()) out += "\n" + body + (body.back() == '\n' ? "" : "\n");
  return out;
}

std::vector<MarkedBlock> markedBlocks(const std::string& text, const std::string& page) {
  std::vector<MarkedBlock> out;
  const auto lines = splitLines(text);
  const auto fenced = fencedLines(lines);
  std::smatch m;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (fenced[i]) continue;
    if (std::regex_match(lines[i], m, kEnd))
      throw InputError(page + ":" + std::to_string(i + 1) + ": '" + m[1].str() +
                       ":end' without its begin");
    if (!std::regex_match(lines[i], m, kBegin)) continue;
    MarkedBlock b{m[1].str(), static_cast<int>(i + 1), ""};
    size_t j = i + 1;
    for (; j < lines.size(); ++j) {
      std::smatch e;
      if (!fenced[j] && std::regex_match(lines[j], e, kEnd) && e[1].str() == b.name) break;
      b.content += lines[j] + "\n";
    }
    if (j == lines.size())
      throw InputError(page + ":" + std::to_string(i + 1) + ": '" + b.name +
                       ":begin' without its end");
    out.push_back(b);
    i = j;
  }
  return out;
}

std::string refreshPage(const std::string& text, const fs::path& store, const fs::path& page) {
  const auto lines = splitLines(text);
  const auto fenced = fencedLines(lines);
  std::map<std::string, StoredRun> runs;
  std::string out;
  std::smatch m;
  for (size_t i = 0; i < lines.size(); ++i) {
    out += lines[i] + "\n";
    if (fenced[i] || !std::regex_match(lines[i], m, kBegin)) continue;
    const std::string name = m[1].str();
    if (name.find('/') == std::string::npos || name == "not-measured") continue;
    const auto slash = name.rfind('/');
    const std::string run = name.substr(0, slash), block = name.substr(slash + 1);
    if (!runs.count(run)) runs.emplace(run, loadRun(store, run));
    out += renderBlock(runs.at(run), block, page);
    size_t j = i + 1;
    for (std::smatch e; j < lines.size(); ++j)
      if (!fenced[j] && std::regex_match(lines[j], e, kEnd) && e[1].str() == name) break;
    if (j == lines.size())
      throw InputError(page.generic_string() + ":" + std::to_string(i + 1) + ": '" + name +
                       ":begin' without its end");
    i = j - 1;
  }
  if (!text.empty() && text.back() != '\n' && !out.empty()) out.pop_back();
  return out;
}

bool scriptWrittenPage(const std::string& text) {
  const auto lines = splitLines(text);
  for (size_t i = 0; i < lines.size() && i < 5; ++i)
    if (lines[i].find("<!-- generated by scripts/") != std::string::npos ||
        lines[i].find("<!-- written by scripts/") != std::string::npos)
      return true;
  return false;
}

std::vector<LooseNumber> looseNumbers(const std::string& text, const std::string& page) {
  std::vector<LooseNumber> out;
  if (report::parseFigureHeader(text)) return out;  // digest-checked (tests/test_figure_docs.cpp)
  if (scriptWrittenPage(text)) return out;
  const auto lines = splitLines(text);
  const auto fenced = fencedLines(lines);
  // A unit or a metric beside a number.
  static const std::regex unit(
      R"((^|[^\w.])(\d[\d,]*(\.\d+)?) ?(ms|s|us|µs|ns|MiB|MB|GiB|GB|KiB|KB|kB|fps|dB|%)(?![\w]))"
      R"(|(^|[^\w.])\d+(\.\d+)?x(?![\w]))"
      R"(|\b(RMSE|FLIP|PSNR|SSIM)( of| =| is|:)? ?-?\d*\.\d+)"
      // A bare number with 3 or more decimals (an error, a ratio), not an option's value.
      R"(|(^|[^\w.=])\d+\.\d{3,}(?![\w.]))");
  static const std::regex allowed(
      R"(<!--\s*not-measured(:begin)?\s*\((paper|tolerance|setting)[^)]*\)\s*-->)");
  static const std::regex allowedEnd(R"(<!--\s*not-measured:end\s*-->)");
  static const std::regex tableUnit(R"(\b(ms|s|MiB|MB|GiB|KiB|fps|dB)\b)");
  static const std::regex tableWord(R"(\b(rmse|flip|psnr|ssim|time|error|memory|fps|hits)\b)",
                                    std::regex::icase);
  static const std::regex numericCell(
      R"(^[~<>=]*\s*-?\d[\d,]*(\.\d+)?(e-?\d+)?\s*(([/,;-]|\[|\]|\s)+\s*-?\d[\d,]*(\.\d+)?(e-?\d+)?\s*\]?)*\s*$)");
  int depth = 0;
  bool quoted = false, prevTable = false, measuredTable = false;
  std::smatch m;
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string& l = lines[i];
    if (!fenced[i] && std::regex_match(l, m, kBegin) && m[1].str() != "not-measured") {
      ++depth;
      continue;
    }
    if (!fenced[i] && std::regex_match(l, m, kEnd) && m[1].str() != "not-measured") {
      depth = std::max(0, depth - 1);
      continue;
    }
    if (!fenced[i] && std::regex_search(l, m, allowed) && m[1].matched) {
      quoted = true;
      continue;
    }
    if (!fenced[i] && std::regex_search(l, allowedEnd)) {
      quoted = false;
      continue;
    }
    const bool table = !l.empty() && l[0] == '|';
    if (table && !prevTable)
      measuredTable = std::regex_search(l, tableUnit) || std::regex_search(l, tableWord);
    const bool header = table && !prevTable;
    prevTable = table;
    if (depth > 0 || quoted || std::regex_search(l, allowed)) continue;
    // The first unit or metric on the line; "95%" is the confidence level of an interval.
    std::string found;
    for (auto it = std::sregex_iterator(l.begin(), l.end(), unit); it != std::sregex_iterator();
         ++it)
      if (const std::string t = trim(it->str()); t != "95%" && t.find("95%") == std::string::npos) {
        found = t;
        break;
      }
    if (!found.empty()) {
      out.push_back({static_cast<int>(i + 1), found, l});
      continue;
    }
    if (table && measuredTable && !header && l.find("---") == std::string::npos) {
      std::istringstream cells(l.substr(1));
      for (std::string c; std::getline(cells, c, '|');) {
        c.erase(std::remove_if(c.begin(), c.end(), [](char ch) { return ch == '`' || ch == '*'; }),
                c.end());
        c = trim(c);
        // A count of passes or layers ("1", "3") is not a measurement; "0.0103", "363" may be.
        const bool measuredLooking =
            c.find('.') != std::string::npos || std::regex_search(c, std::regex(R"(\d\d)"));
        if (!c.empty() && measuredLooking && std::regex_match(c, numericCell)) {
          out.push_back({static_cast<int>(i + 1), c, l});
          break;
        }
      }
    }
  }
  (void)page;
  return out;
}

std::vector<fs::path> docPages(const fs::path& root) {
  std::vector<fs::path> out{"README.md"};
  for (const char* dir : {"docs", "docs/figures"}) {
    std::vector<fs::path> here;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(root / dir, ec))
      if (e.path().extension() == ".md") here.push_back(fs::path(dir) / e.path().filename());
    std::sort(here.begin(), here.end());
    out.insert(out.end(), here.begin(), here.end());
  }
  return out;
}

std::vector<StaleBlock> staleBlocks(const fs::path& root, const ChangedFiles& changed,
                                    const FigureDepends& figureDepends) {
  std::vector<StaleBlock> out;
  std::map<std::string, StoredRun> runs;
  for (const auto& page : docPages(root)) {
    const std::string text = readTextFile(root / page);
    if (const auto h = report::parseFigureHeader(text); h && figureDepends) {
      auto files = changed(h->commit, figureDepends(h->name));
      if (!files.empty()) out.push_back({page, "figure " + h->name, h->commit, files});
    }
    for (const auto& b : markedBlocks(text, page.generic_string())) {
      if (!b.fromStore()) continue;
      const auto slash = b.name.rfind('/');
      const std::string run = b.name.substr(0, slash), block = b.name.substr(slash + 1);
      if (!runs.count(run)) runs.emplace(run, loadRun(root / "docs/results", run));
      const StoredRun& r = runs.at(run);
      const std::string commit = r.meta["commit"].get<std::string>();
      auto files = changed(commit, blockDepends(r, block));
      if (!files.empty()) out.push_back({page, b.name, commit, files});
    }
  }
  return out;
}

}  // namespace sb::docs
