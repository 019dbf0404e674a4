// A cost model per backend and device: the median frame time of a run's cases fitted
// against their exact work counters (frame_work) with non-negative least squares, so a
// reader sees what a fragment, a byte and a pass cost on that device, and which case
// takes far longer than its work explains.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace sb::report {

// Non-negative least squares (Lawson & Hanson 1974, ch. 23, the active-set method):
// the x >= 0 minimising |A x - b|, with A given as rows (all of one length).
// Columns should be of similar scale (the caller scales them).
std::vector<double> nnls(const std::vector<std::vector<double>>& rows,
                         const std::vector<double>& b);

struct CostTerm {
  std::string name;        // "fragments", "vertices", "compute", "bytes", "passes", "constant"
  std::string unit;        // what the coefficient is per: "ms per million fragments"
  double coefficient = 0;  // in that unit
};

struct CostCase {
  std::string caseId, technique;
  double measured = 0;  // frame_ms.median
  // By the fit over the other cases in the fit (leave one out); for a case left out of
  // the fit, by the fit.
  std::optional<double> predicted;
  std::optional<double> ratio;  // measured / predicted
  bool inefficient = false;     // far slower than its work predicts
  bool inFit = true;            // false: left out of the fit as inefficient
};

struct CostModel {
  std::string backend, device;
  bool fitted = false;
  std::string note;             // why there is no fit, or what was left out
  std::optional<double> r2;     // over the cases in the fit
  std::optional<double> r2All;  // the same coefficients over every case
  int fitCases = 0;
  std::vector<CostTerm> terms;
  std::vector<CostCase> cases;  // by measured / predicted, highest first
};

// A case is "inefficient" when measured > kInefficientRatio x predicted and the excess is
// more than kInefficientSpread robust residual spreads (1.4826 x median |residual|); the
// fit is redone without such cases, at most kFitRounds times in all.
inline constexpr double kInefficientRatio = 2.0;
inline constexpr double kInefficientSpread = 3.0;
inline constexpr int kFitRounds = 4;

// One model per backend and device (in order of first appearance) over the results that
// ran and carry frame_work (or per-pass work). Fewer cases than terms + 2: no fit.
std::vector<CostModel> fitCostModels(const std::vector<const nlohmann::json*>& results);

// cost_model.json: {"models": [{backend, device, fitted, note, r2, terms, cases}]}.
nlohmann::json costModelsJson(const std::vector<CostModel>& models);

}  // namespace sb::report
