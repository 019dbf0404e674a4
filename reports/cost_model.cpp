#include "reports/cost_model.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "reports/report_data.h"

namespace sb::report {

namespace {

// Unconstrained least squares over the columns `cols` of A (Householder QR, so nearly
// collinear counters do not square the condition number as normal equations would);
// the other entries of the result are 0, as is the entry of a column found dependent.
std::vector<double> leastSquares(const std::vector<std::vector<double>>& rows,
                                 const std::vector<double>& b, const std::vector<int>& cols,
                                 std::size_t n) {
  const std::size_t m = rows.size(), p = cols.size();
  std::vector<std::vector<double>> a(m, std::vector<double>(p));
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t k = 0; k < p; ++k) a[i][k] = rows[i][cols[k]];
  std::vector<double> y = b;
  std::vector<bool> dependent(p, false);
  for (std::size_t k = 0; k < p && k < m; ++k) {
    double norm = 0;
    for (std::size_t i = k; i < m; ++i) norm += a[i][k] * a[i][k];
    norm = std::sqrt(norm);
    if (norm < 1e-12) {
      dependent[k] = true;
      continue;
    }
    const double alpha = a[k][k] > 0 ? -norm : norm;
    std::vector<double> v(m, 0.0);
    for (std::size_t i = k; i < m; ++i) v[i] = a[i][k];
    v[k] -= alpha;
    double vv = 0;
    for (std::size_t i = k; i < m; ++i) vv += v[i] * v[i];
    if (vv == 0) continue;
    auto reflect = [&](auto&& get) {
      double dot = 0;
      for (std::size_t i = k; i < m; ++i) dot += v[i] * get(i);
      const double f = 2 * dot / vv;
      for (std::size_t i = k; i < m; ++i) get(i) -= f * v[i];
    };
    for (std::size_t c = k; c < p; ++c) reflect([&](std::size_t i) -> double& { return a[i][c]; });
    reflect([&](std::size_t i) -> double& { return y[i]; });
  }
  std::vector<double> s(p, 0.0);
  for (std::size_t k = std::min(p, m); k-- > 0;) {
    if (dependent[k] || std::abs(a[k][k]) < 1e-10) continue;
    double sum = y[k];
    for (std::size_t c = k + 1; c < p; ++c) sum -= a[k][c] * s[c];
    s[k] = sum / a[k][k];
  }
  std::vector<double> out(n, 0.0);
  for (std::size_t k = 0; k < p; ++k) out[cols[k]] = s[k];
  return out;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

std::optional<double> passExecutions(const json& r) {
  const json* passes = find(r, {"passes"});
  if (!passes || !passes->is_array() || passes->empty()) return std::nullopt;
  double sum = 0;
  for (const json& p : *passes) sum += number(find(p, {"executions"})).value_or(1);
  return sum;
}

struct TermSpec {
  const char* name;
  const char* unit;
  double per;  // counter units per coefficient unit (1e6: per million)
  std::optional<double> (*value)(const json& r);
};

const TermSpec kTerms[] = {
    {"fragments", "ms per million fragments", 1e6,
     [](const json& r) { return frameCounter(r, "fragment_invocations"); }},
    {"vertices", "ms per million vertices", 1e6,
     [](const json& r) { return frameCounter(r, "vertex_invocations"); }},
    {"compute", "ms per million compute invocations", 1e6,
     [](const json& r) { return frameCounter(r, "compute_invocations"); }},
    {"bytes", "ms per MiB written, read or bound as storage", 1024.0 * 1024.0, frameBytes},
    {"passes", "ms per pass execution", 1, passExecutions},
    {"constant", "ms per frame", 1, [](const json&) -> std::optional<double> { return 1.0; }},
};

struct Sample {
  const json* r;
  double ms;
  std::vector<double> x;  // per kTerms entry; NaN where absent
};

// The fit over `rows` (scaled by column), returned in unscaled units.
std::vector<double> fitScaled(const std::vector<std::vector<double>>& rows,
                              const std::vector<double>& y, const std::vector<double>& scale) {
  std::vector<std::vector<double>> scaled = rows;
  for (auto& row : scaled)
    for (std::size_t j = 0; j < row.size(); ++j) row[j] /= scale[j];
  std::vector<double> x = nnls(scaled, y);
  for (std::size_t j = 0; j < x.size(); ++j) x[j] /= scale[j];
  return x;
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

CostModel fitOne(const std::string& backend, const std::string& device,
                 const std::vector<Sample>& samples, std::size_t withoutCounters) {
  CostModel m;
  m.backend = backend;
  m.device = device;
  if (withoutCounters)
    m.note = std::to_string(withoutCounters) + " case" + (withoutCounters > 1 ? "s" : "") +
             " without work counters left out";
  // A term is used when every case has it and it is not zero throughout (compute on a
  // run without compute passes would be a column of zeros).
  std::vector<int> used;
  for (std::size_t t = 0; t < std::size(kTerms); ++t) {
    bool all = !samples.empty(), any = false;
    for (const Sample& s : samples) {
      all &= std::isfinite(s.x[t]);
      any |= std::isfinite(s.x[t]) && s.x[t] != 0;
    }
    if (all && any) used.push_back(static_cast<int>(t));
  }
  for (int t : used) m.terms.push_back({kTerms[t].name, kTerms[t].unit, 0});
  if (samples.empty()) {
    m.note = "no case has work counters (results from before frame_work)";
    return m;
  }
  if (samples.size() < used.size() + 2) {
    m.note = "too few cases to fit: " + std::to_string(samples.size()) + " with work counters, " +
             std::to_string(used.size() + 2) + " needed for " + std::to_string(used.size()) +
             " terms" + (m.note.empty() ? "" : "; " + m.note);
    for (const Sample& s : samples)
      m.cases.push_back({caseId(*s.r), shortTechniqueOf(*s.r, true, true), s.ms, {}, {}, false});
    return m;
  }
  std::vector<std::vector<double>> rows;
  std::vector<double> y;
  std::vector<double> scale(used.size(), 0.0);
  for (const Sample& s : samples) {
    std::vector<double> row;
    for (std::size_t k = 0; k < used.size(); ++k) {
      row.push_back(s.x[used[k]]);
      scale[k] = std::max(scale[k], std::abs(s.x[used[k]]));
    }
    rows.push_back(std::move(row));
    y.push_back(s.ms);
  }
  for (double& sc : scale)
    if (sc == 0) sc = 1;
  // A case whose time its work does not explain (a heavy shader, a stall) would drag the
  // constant and the costs of every other case towards itself: the fit is repeated
  // without the cases it marks until the marked set settles (a few rounds at most).
  const std::size_t n = rows.size();
  std::vector<bool> keep(n, true);
  std::vector<double> coef, predicted(n, 0.0);
  std::vector<bool> marked(n, false);
  for (int round = 0; round < kFitRounds; ++round) {
    std::vector<std::vector<double>> kr;
    std::vector<double> ky;
    for (std::size_t i = 0; i < n; ++i)
      if (keep[i]) kr.push_back(rows[i]), ky.push_back(y[i]);
    coef = fitScaled(kr, ky, scale);
    std::vector<double> absRes;
    for (std::size_t i = 0; i < n; ++i)
      if (keep[i]) absRes.push_back(std::abs(y[i] - dot(rows[i], coef)));
    const double spread = 1.4826 * median(absRes);
    const double floor = 0.01 * median(y);  // an exact fit has no spread: ignore rounding
    // A case in the fit is predicted by the fit over the others, so that a slow case
    // cannot pull the fit towards itself and hide (a few dozen refits are cheap).
    for (std::size_t i = 0; i < n; ++i) {
      if (keep[i]) {
        std::vector<std::vector<double>> others;
        std::vector<double> yo;
        for (std::size_t j = 0; j < n; ++j)
          if (j != i && keep[j]) others.push_back(rows[j]), yo.push_back(y[j]);
        predicted[i] = dot(rows[i], fitScaled(others, yo, scale));
      } else {
        predicted[i] = dot(rows[i], coef);
      }
      const double excess = y[i] - predicted[i];
      marked[i] = (predicted[i] <= 0 || y[i] / predicted[i] > kInefficientRatio) &&
                  excess > std::max(kInefficientSpread * spread, floor);
    }
    std::vector<bool> next(n);
    for (std::size_t i = 0; i < n; ++i) next[i] = !marked[i];
    if (next == keep || round + 1 == kFitRounds ||
        static_cast<std::size_t>(std::count(next.begin(), next.end(), true)) < used.size() + 2)
      break;
    keep = next;
  }
  m.fitted = true;
  for (std::size_t k = 0; k < used.size(); ++k)
    m.terms[k].coefficient = coef[k] * kTerms[used[k]].per;
  auto r2 = [&](bool all) {
    double mean = 0, count = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (all || keep[i]) mean += y[i], ++count;
    mean /= count;
    double ssRes = 0, ssTot = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (!all && !keep[i]) continue;
      const double res = y[i] - dot(rows[i], coef);
      ssRes += res * res;
      ssTot += (y[i] - mean) * (y[i] - mean);
    }
    return ssTot > 0 ? 1 - ssRes / ssTot : (ssRes < 1e-18 ? 1.0 : 0.0);
  };
  m.r2 = r2(false);
  m.r2All = r2(true);
  m.fitCases = static_cast<int>(std::count(keep.begin(), keep.end(), true));
  for (std::size_t i = 0; i < n; ++i) {
    CostCase c{caseId(*samples[i].r),
               shortTechniqueOf(*samples[i].r, true, true),
               y[i],
               predicted[i],
               {},
               marked[i],
               keep[i]};
    if (predicted[i] > 0) c.ratio = y[i] / predicted[i];
    m.cases.push_back(std::move(c));
  }
  std::stable_sort(m.cases.begin(), m.cases.end(), [](const CostCase& a, const CostCase& b) {
    const double ra = a.ratio.value_or(INFINITY), rb = b.ratio.value_or(INFINITY);
    return ra > rb;
  });
  return m;
}

}  // namespace

std::vector<double> nnls(const std::vector<std::vector<double>>& rows,
                         const std::vector<double>& b) {
  const std::size_t n = rows.empty() ? 0 : rows[0].size();
  std::vector<double> x(n, 0.0);
  std::vector<bool> passive(n, false);
  auto gradient = [&] {
    std::vector<double> w(n, 0.0);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double r = b[i] - dot(rows[i], x);
      for (std::size_t j = 0; j < n; ++j) w[j] += rows[i][j] * r;
    }
    return w;
  };
  double bNorm = 0;
  for (double v : b) bNorm = std::max(bNorm, std::abs(v));
  const double tol = 1e-10 * std::max(1.0, bNorm) * static_cast<double>(rows.size());
  for (std::size_t iter = 0; iter < 3 * n + 10; ++iter) {
    const std::vector<double> w = gradient();
    int t = -1;
    for (std::size_t j = 0; j < n; ++j)
      if (!passive[j] && w[j] > tol && (t < 0 || w[j] > w[t])) t = static_cast<int>(j);
    if (t < 0) break;  // Kuhn-Tucker conditions hold
    passive[t] = true;
    for (std::size_t inner = 0; inner < 3 * n + 10; ++inner) {
      std::vector<int> cols;
      for (std::size_t j = 0; j < n; ++j)
        if (passive[j]) cols.push_back(static_cast<int>(j));
      const std::vector<double> s = leastSquares(rows, b, cols, n);
      bool feasible = true;
      for (int j : cols) feasible &= s[j] > 0;
      if (feasible) {
        x = s;
        break;
      }
      // Step from x towards s as far as keeps every passive entry non-negative, then
      // drop the entries that reached 0.
      double alpha = 1;
      for (int j : cols)
        if (s[j] <= 0) alpha = std::min(alpha, x[j] / (x[j] - s[j]));
      for (std::size_t j = 0; j < n; ++j) {
        x[j] += alpha * (s[j] - x[j]);
        if (passive[j] && x[j] <= 1e-14) passive[j] = false, x[j] = 0;
      }
    }
  }
  return x;
}

std::vector<CostModel> fitCostModels(const std::vector<const json*>& results) {
  std::vector<std::pair<std::string, std::string>> keys;
  std::map<std::pair<std::string, std::string>, std::vector<Sample>> samples;
  std::map<std::pair<std::string, std::string>, std::size_t> without;
  for (const json* r : results) {
    const auto ms = frameMs(*r);
    if (!failureOf(*r).empty() || !ms) continue;
    const std::pair key{backendOf(*r), text(find(*r, {"device"}))};
    if (!samples.count(key) && !without.count(key)) keys.push_back(key);
    Sample s{r, *ms, {}};
    for (const TermSpec& t : kTerms) s.x.push_back(t.value(*r).value_or(NAN));
    // Without the counters that every device has (fragments, bytes) a case says nothing.
    if (!std::isfinite(s.x[0]) || !std::isfinite(s.x[3])) {
      ++without[key];
      continue;
    }
    samples[key].push_back(std::move(s));
  }
  std::vector<CostModel> out;
  for (const auto& key : keys)
    out.push_back(fitOne(key.first, key.second, samples[key], without[key]));
  return out;
}

json costModelsJson(const std::vector<CostModel>& models) {
  json out = {{"models", json::array()}};
  for (const CostModel& m : models) {
    json jm = {{"backend", m.backend}, {"device", m.device}, {"fitted", m.fitted}};
    if (!m.note.empty()) jm["note"] = m.note;
    jm["r2"] = m.r2 ? json(*m.r2) : json(nullptr);
    jm["r2_all_cases"] = m.r2All ? json(*m.r2All) : json(nullptr);
    jm["fit_cases"] = m.fitCases;
    jm["terms"] = json::array();
    for (const CostTerm& t : m.terms)
      jm["terms"].push_back({{"name", t.name},
                             {"unit", t.unit},
                             {"coefficient", m.fitted ? json(t.coefficient) : json(nullptr)}});
    jm["cases"] = json::array();
    for (const CostCase& c : m.cases)
      jm["cases"].push_back({{"case", c.caseId},
                             {"technique", c.technique},
                             {"measured_ms", c.measured},
                             {"predicted_ms", c.predicted ? json(*c.predicted) : json(nullptr)},
                             {"ratio", c.ratio ? json(*c.ratio) : json(nullptr)},
                             {"inefficient", c.inefficient},
                             {"in_fit", c.inFit}});
    out["models"].push_back(std::move(jm));
  }
  return out;
}

}  // namespace sb::report
