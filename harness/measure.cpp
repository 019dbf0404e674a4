#include "harness/measure.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "base/errors.h"
#include "harness/sweep.h"

namespace sb {

int Measurement::outlierCount() const {
  int n = 0;
  for (bool o : outliers) n += o;
  return n;
}

void checkRepetitionOrder(int minReps, int maxReps) {
  if (maxReps < minReps)
    throw InputError("--max-reps " + std::to_string(maxReps) + ": below --min-reps " +
                     std::to_string(minReps));
}

void checkRepetitionOptions(const RepetitionOptions& o, int leastMinReps) {
  if (o.minReps < leastMinReps)
    throw InputError("--min-reps " + std::to_string(o.minReps) + ": at least " +
                     std::to_string(leastMinReps) +
                     (leastMinReps > 1 ? " (an interval needs two samples)" : ""));
  // The options' ranges are the run-options table's (harness/run_options.h), checked where
  // they are read; the rule between them holds for resolved rounds too.
  checkRepetitionOrder(o.minReps, o.maxReps);
}

std::vector<Measurement> measureInterleaved(const std::vector<std::function<double()>>& cases,
                                            const RepetitionOptions& o, int leastMinReps) {
  checkRepetitionOptions(o, leastMinReps);
  const std::size_t n = cases.size();
  std::vector<Measurement> m(n);
  std::vector<bool> failed(n, false);
  for (int round = 0; round < o.maxReps; ++round) {
    // Rotating the first case: no case always runs right after a warm-up or a cold cache.
    std::vector<double> sample(n);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = (k + std::size_t(round)) % n;
      if (!failed[i]) sample[i] = cases[i]();
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (failed[i]) continue;
      if (std::isnan(sample[i]))
        failed[i] = true;
      else
        m[i].samples.push_back(sample[i]);
    }
    if (round + 1 < o.minReps) continue;
    if (o.targetCiPct == 0) break;  // no target: exactly --min-reps rounds
    bool precise = true;
    for (std::size_t i = 0; i < n; ++i) {
      if (failed[i]) continue;
      m[i].median = bootstrapMedian(m[i].samples);
      precise = precise && m[i].median.relativeHalfWidth() * 100 <= o.targetCiPct;
    }
    if (precise) break;
  }
  for (auto& c : m) {
    if (c.samples.empty()) continue;
    c.median = bootstrapMedian(c.samples);
    c.outliers = tukeyOutliers(c.samples);
  }
  return m;
}

Interval ratioInterval(const Measurement& num, const Measurement& den) {
  return bootstrapRatio(num.samples, den.samples, /*paired=*/true);
}

Interval printRatio(std::ostream& out, const std::string& label, const Measurement& num,
                    const Measurement& den, const std::string& paper,
                    const std::optional<OrderingClaim>& claim) {
  const Interval r = ratioInterval(num, den);
  out << "  " << label << ": " << formatInterval(r) << "  (" << paper << ")\n";
  if (claim) {
    // A percentile bootstrap of 2-4 rounds has too few distinct resamples to be an interval.
    const bool tooFew = std::min(num.samples.size(), den.samples.size()) < kMinRoundsForVerdict;
    const std::string v =
        tooFew ? "undecided" : orderingVerdict(r, claim->bound, claim->claimBelow);
    std::ostringstream bound;
    bound << claim->bound;
    out << "    paper's ordering (" << claim->text << ", ratio "
        << (claim->claimBelow ? "< " : "> ") << bound.str() << "): "
        << (tooFew ? "undecided (fewer than " + std::to_string(kMinRoundsForVerdict) +
                         " rounds: no interval to judge by)"
            : v == "undecided" ? "undecided (the interval contains " + bound.str() + ")"
                               : v + " with 95% confidence")
        << "\n";
  }
  return r;
}

std::string describe(const Measurement& m) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << m.median.estimate << " ms [" << m.median.low << ", "
    << m.median.high << "], " << m.samples.size() << " reps";
  if (const int k = m.outlierCount()) s << ", " << k << " outlier" << (k > 1 ? "s" : "");
  return s.str();
}

std::string machineState() {
  std::ostringstream s;
  const auto load = loadAverage();
  if (load.is_null())
    s << "load unknown";
  else
    s << "load " << load["1min"].get<double>() << " " << load["5min"].get<double>() << " "
      << load["15min"].get<double>();
  const std::string g = cpuGovernor();
  s << ", CPU governor " << (g.empty() ? "not visible" : g);
  return s.str();
}

}  // namespace sb
