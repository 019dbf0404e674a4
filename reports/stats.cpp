#include "reports/stats.h"

#include <algorithm>
#include <cmath>
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
