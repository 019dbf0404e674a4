#include "reports/stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <numeric>
#include <utility>

namespace sb {

Stats summarize(std::vector<double> v) {
  Stats s;
  s.count = static_cast<int>(v.size());
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  s.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  s.min = v.front();
  s.max = v.back();
  s.mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(n);
  double sq = 0;
  for (double x : v) sq += (x - s.mean) * (x - s.mean);
  s.stddev = n > 1 ? std::sqrt(sq / static_cast<double>(n - 1)) : 0.0;
  return s;
}

double median(std::vector<double> values) { return summarize(std::move(values)).median; }

namespace {

// P(U >= k) for k = 0..m*n, for samples of m <= n values without ties.
std::vector<double> exactUpperTails(int m, int n) {
  const int maxU = m * n;
  // count[i][k]: the orderings of i x-values and j y-values (j = the outer loop) with U = k.
  // The largest value is either a y above all i x-values (adds i to U, one y fewer) or an x
  // (adds nothing, one x fewer): N(i, j, k) = N(i, j-1, k-i) + N(i-1, j, k). Counts are kept
  // in doubles (C(m+n, m) overflows 64-bit integers for large samples; the relative error
  // stays at rounding level). Updated in place over j, k descending so N(i, j-1, k-i) is
  // still the previous row's value.
  std::vector<std::vector<double>> count(m + 1, std::vector<double>(maxU + 1, 0.0));
  for (int i = 0; i <= m; ++i) count[i][0] = 1.0;  // j = 0: one ordering, U = 0
  for (int j = 1; j <= n; ++j)
    for (int i = 1; i <= m; ++i)
      for (int k = maxU; k >= 0; --k)
        count[i][k] = (k >= i ? count[i][k - i] : 0.0) + count[i - 1][k];
  std::vector<double> tail(maxU + 1);
  double sum = 0;
  for (int k = maxU; k >= 0; --k) tail[k] = (sum += count[m][k]);
  for (double& t : tail) t = std::min(1.0, t / sum);
  return tail;
}

}  // namespace

double mannWhitneyExactUpperTail(int m, int n, double u) {
  if (m <= 0 || n <= 0) return 1.0;
  if (m > n) std::swap(m, n);  // U's null distribution depends on {m, n} only; keep rows short
  // One table per pair of sample sizes (a comparison of many cases reuses a few sizes).
  static std::mutex mutex;
  static std::map<std::pair<int, int>, std::vector<double>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto it = cache.find({m, n});
  if (it == cache.end()) it = cache.emplace(std::pair{m, n}, exactUpperTails(m, n)).first;
  const int from = static_cast<int>(std::ceil(u - 1e-9));
  if (from <= 0) return 1.0;
  if (from > m * n) return 0.0;
  return it->second[from];
}

double mannWhitneyMinP(int m, int n) {
  if (m <= 0 || n <= 0) return 1.0;
  double c = 1.0;  // C(m+n, m) as a running product
  for (int k = 1; k <= m; ++k) c = c * static_cast<double>(n + k) / static_cast<double>(k);
  return 1.0 / c;
}

double signedRankMinP(int n) { return n <= 0 ? 1.0 : std::ldexp(1.0, -n); }

RankTest signedRankGreater(const std::vector<double>& d) {
  RankTest r;
  std::vector<double> nonzero;
  for (double v : d)
    if (v != 0.0) nonzero.push_back(v);
  const std::size_t n = nonzero.size();
  if (n == 0) return r;
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::abs(nonzero[a]) < std::abs(nonzero[b]);
  });
  std::vector<double> rank(n);
  for (std::size_t i = 0; i < n;) {  // average ranks over ties in |d|
    std::size_t j = i;
    while (j + 1 < n && std::abs(nonzero[order[j + 1]]) == std::abs(nonzero[order[i]])) ++j;
    for (std::size_t k = i; k <= j; ++k) rank[order[k]] = double(i + j) / 2.0 + 1.0;
    i = j + 1;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (nonzero[i] > 0) r.u += rank[i];
  if (n <= static_cast<std::size_t>(kSignedRankExactLimit)) {
    // Every sign pattern is equally likely under the null hypothesis.
    std::size_t hits = 0;
    for (std::size_t signs = 0; signs < (std::size_t{1} << n); ++signs) {
      double w = 0;
      for (std::size_t i = 0; i < n; ++i)
        if (signs >> i & 1u) w += rank[i];
      if (w >= r.u - 1e-9) ++hits;
    }
    r.p = double(hits) / double(std::size_t{1} << n);
    r.exact = true;
    return r;
  }
  double tieSum = 0;  // sum over tie groups of (t^3 - t)
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i;
    while (j + 1 < n && rank[order[j + 1]] == rank[order[i]]) ++j;
    const double t = double(j - i + 1);
    tieSum += t * t * t - t;
    i = j + 1;
  }
  const double nn = double(n);
  const double mean = nn * (nn + 1) / 4.0;
  const double var = nn * (nn + 1) * (2 * nn + 1) / 24.0 - tieSum / 48.0;
  const double z = (r.u - mean - 0.5) / std::sqrt(var);
  r.p = 0.5 * std::erfc(z / std::sqrt(2.0));
  return r;
}

RankTest mannWhitneyGreater(const std::vector<double>& x, const std::vector<double>& y) {
  RankTest r;
  const std::size_t m = x.size(), n = y.size();
  if (m == 0 || n == 0) return r;
  for (double a : x)
    for (double b : y) r.u += a < b ? 1.0 : (a == b ? 0.5 : 0.0);

  // Ties in the pooled sample: sizes of the groups of equal values.
  std::vector<double> pooled(x);
  pooled.insert(pooled.end(), y.begin(), y.end());
  std::sort(pooled.begin(), pooled.end());
  double tieSum = 0;  // sum of t^3 - t over the tie groups
  for (std::size_t i = 0; i < pooled.size();) {
    std::size_t j = i;
    while (j < pooled.size() && pooled[j] == pooled[i]) ++j;
    const double t = static_cast<double>(j - i);
    tieSum += t * t * t - t;
    i = j;
  }

  const double mm = static_cast<double>(m), nn = static_cast<double>(n);
  if (tieSum == 0 && mm * nn <= kMannWhitneyExactLimit) {
    r.exact = true;
    r.p = mannWhitneyExactUpperTail(static_cast<int>(m), static_cast<int>(n), r.u);
    return r;
  }
  const double total = mm + nn;
  const double variance = mm * nn / 12.0 * ((total + 1.0) - tieSum / (total * (total - 1.0)));
  if (!(variance > 0)) return r;  // every value equal: no evidence either way
  const double z = (r.u - mm * nn / 2.0 - 0.5) / std::sqrt(variance);
  r.p = std::clamp(0.5 * std::erfc(z / std::sqrt(2.0)), 0.0, 1.0);
  return r;
}

}  // namespace sb

namespace sb {

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const double pos = std::clamp(q, 0.0, 1.0) * static_cast<double>(v.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(pos);
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

std::vector<bool> tukeyOutliers(const std::vector<double>& values) {
  std::vector<bool> out(values.size(), false);
  if (values.size() < 4) return out;  // quartiles of fewer values say nothing
  const double q1 = quantile(values, 0.25), q3 = quantile(values, 0.75);
  const double iqr = q3 - q1;
  for (std::size_t i = 0; i < values.size(); ++i)
    out[i] = values[i] < q1 - 1.5 * iqr || values[i] > q3 + 1.5 * iqr;
  return out;
}

double Interval::relativeHalfWidth() const {
  return estimate != 0 ? 0.5 * (high - low) / std::abs(estimate) : 0.0;
}

namespace {

// A small, fast generator with a stated seed (SplitMix64, Steele et al. 2014): the intervals
// are reproducible run to run, unlike std::random_device.
struct SplitMix {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }
};

Interval percentileInterval(double estimate, std::vector<double>& draws, double confidence) {
  const double a = (1 - confidence) / 2;
  return {estimate, quantile(draws, a), quantile(draws, 1 - a)};
}

double medianInPlace(std::vector<double>& v) {
  const std::size_t n = v.size(), h = n / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(h), v.end());
  if (n % 2) return v[h];
  const double upper = v[h];
  return 0.5 * (*std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(h)) + upper);
}

}  // namespace

Interval bootstrapMedian(const std::vector<double>& values, double confidence, int resamples,
                         std::uint64_t seed) {
  const double m = median(values);
  if (values.size() < 2) return {m, m, m};
  SplitMix rng{seed};
  std::vector<double> draws, x(values.size());
  draws.reserve(static_cast<std::size_t>(resamples));
  for (int r = 0; r < resamples; ++r) {
    for (double& v : x) v = values[rng.below(values.size())];
    draws.push_back(medianInPlace(x));
  }
  return percentileInterval(m, draws, confidence);
}

Interval bootstrapRatio(const std::vector<double>& num, const std::vector<double>& den, bool paired,
                        double confidence, int resamples, std::uint64_t seed) {
  const double d = median(den);
  const double estimate = d != 0 ? median(num) / d : 0.0;
  if (num.size() < 2 || den.size() < 2 || d == 0) return {estimate, estimate, estimate};
  paired = paired && num.size() == den.size();
  SplitMix rng{seed};
  std::vector<double> draws, a(num.size()), b(den.size());
  draws.reserve(static_cast<std::size_t>(resamples));
  for (int r = 0; r < resamples; ++r) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      const std::size_t k = rng.below(num.size());
      a[i] = num[k];
      if (paired) b[i] = den[k];
    }
    if (!paired)
      for (double& v : b) v = den[rng.below(den.size())];
    const double db = medianInPlace(b);
    if (db != 0) draws.push_back(medianInPlace(a) / db);
  }
  return percentileInterval(estimate, draws, confidence);
}

std::string formatInterval(const Interval& i, int precision) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.*f [%.*f, %.*f]", precision, i.estimate, precision, i.low,
                precision, i.high);
  return buf;
}

std::string orderingVerdict(const Interval& ratio, double bound, bool claimBelow) {
  const bool below = ratio.high<bound, above = ratio.low> bound;
  if (claimBelow ? below : above) return "holds";
  if (claimBelow ? above : below) return "fails";
  return "undecided";
}

namespace {

// Pettitt's statistic standardized per split: Z_k = D_k / sd(D_k), D_k = sum_{i<k<=j}
// sign(x_j - x_i), sd^2 = k (n-k) (n+1) / 3 (the Mann-Whitney variance, no ties). The split
// with the largest |Z| over k in [minSeg, n - minSeg]; standardizing keeps splits near the
// ends (a recent change) as detectable as those in the middle.
std::pair<int, double> pettittMax(const std::vector<double>& x, int minSeg) {
  const int n = static_cast<int>(x.size());
  auto sign = [](double d) { return d > 0 ? 1.0 : (d < 0 ? -1.0 : 0.0); };
  double d = 0;
  int best = -1;
  double bestZ = -1;
  for (int k = 1; k < n; ++k) {
    // Moving x[k-1] from the second part to the first: its pairs with the first part leave D,
    // its pairs with the rest of the second part enter it.
    for (int j = 0; j < n; ++j)
      if (j != k - 1) d += j > k - 1 ? sign(x[j] - x[k - 1]) : -sign(x[k - 1] - x[j]);
    if (k < minSeg || n - k < minSeg) continue;
    const double z = std::abs(d) / std::sqrt(double(k) * double(n - k) * double(n + 1) / 3.0);
    if (z > bestZ) bestZ = z, best = k;
  }
  return {best, bestZ};
}

void segment(const std::vector<double>& x, int from, int to, const ChangePointOptions& o,
             std::uint64_t& seed, std::vector<ChangePoint>& out) {
  if (to - from < 2 * o.minSegment) return;
  std::vector<double> part(x.begin() + from, x.begin() + to);
  const auto [k, z] = pettittMax(part, o.minSegment);
  if (k < 0) return;
  SplitMix rng{seed++};
  int atLeast = 0;
  std::vector<double> shuffled = part;
  for (int r = 0; r < o.permutations; ++r) {
    for (std::size_t i = shuffled.size() - 1; i > 0; --i)
      std::swap(shuffled[i], shuffled[rng.below(i + 1)]);  // Fisher-Yates
    if (pettittMax(shuffled, o.minSegment).second >= z - 1e-12) ++atLeast;
  }
  const double p = (1.0 + atLeast) / (1.0 + o.permutations);
  if (p >= o.alpha) return;
  ChangePoint c;
  c.index = from + k;
  c.before = median(std::vector<double>(part.begin(), part.begin() + k));
  c.after = median(std::vector<double>(part.begin() + k, part.end()));
  c.size = c.before != 0 ? c.after / c.before - 1 : 0;
  c.p = p;
  out.push_back(c);
  segment(x, from, from + k, o, seed, out);
  segment(x, from + k, to, o, seed, out);
}

}  // namespace

std::vector<ChangePoint> findChangePoints(const std::vector<double>& series,
                                          const ChangePointOptions& options) {
  std::vector<ChangePoint> out;
  std::uint64_t seed = options.seed;
  segment(series, 0, static_cast<int>(series.size()), options, seed, out);
  std::sort(out.begin(), out.end(),
            [](const ChangePoint& a, const ChangePoint& b) { return a.index < b.index; });
  return out;
}

}  // namespace sb
