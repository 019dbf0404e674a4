// Summary statistics over repetitions (median, min, max, mean, standard deviation) and the
// rank test that `compare-runs` uses to judge whether a change is more than noise.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sb {

struct Stats {
  double median = 0, min = 0, max = 0, mean = 0, stddev = 0;
  int count = 0;
};

Stats summarize(std::vector<double> values);

// Median of the values (the mean of the middle two for an even count); 0 when empty.
double median(std::vector<double> values);

// One-sided Mann-Whitney U test (Wilcoxon rank-sum) of "y tends to be larger than x".
//   u: the statistic for y, #pairs (x_i < y_j) + 0.5 * #pairs (x_i == y_j), in [0, m*n].
//   p: P(U >= u) under the null hypothesis that x and y come from one distribution.
//   exact: p comes from the exact distribution of U (no ties in the pooled sample and
//     m*n <= kMannWhitneyExactLimit); otherwise from the normal approximation with tie
//     correction and continuity correction (p = 1 when every value is equal).
// p = 1 when either sample is empty.
struct RankTest {
  double u = 0;
  double p = 1;
  bool exact = false;
};
inline constexpr int kMannWhitneyExactLimit = 2500;
RankTest mannWhitneyGreater(const std::vector<double>& x, const std::vector<double>& y);

// P(U >= u) for samples of m and n values without ties (exact null distribution of U, counted
// with the recurrence over the largest value of the pooled sample).
double mannWhitneyExactUpperTail(int m, int n, double u);

// The smallest p-value the test can give for samples of m and n values: 1 / C(m+n, m) (all of y
// above all of x). A difference cannot be significant at alpha when this is >= alpha (3 vs 3
// repetitions give 0.05 at best).
double mannWhitneyMinP(int m, int n);

// One-sided Wilcoxon signed-rank test of "the differences d tend to be above 0", for paired
// measurements (each pair taken at the same time, so the machine's drift cancels).
//   u: the sum of the ranks of |d_i| (ties averaged) over the positive d_i; zeros are dropped.
//   p: P(W >= u) under the null hypothesis that each difference is as likely + as -, counted
//     exactly over the 2^n sign patterns for n <= kSignedRankExactLimit, else the normal
//     approximation with continuity correction. p = 1 when no difference is non-zero.
inline constexpr int kSignedRankExactLimit = 20;
RankTest signedRankGreater(const std::vector<double>& d);

// The smallest p the signed-rank test can give for n pairs: 2^-n (every difference above 0).
double signedRankMinP(int n);

// The q-quantile (0..1) of the values, linear between order statistics (R's type 7); 0 when
// empty.
double quantile(std::vector<double> values, double q);

// Outliers by Tukey's fences: values below Q1 - 1.5 IQR or above Q3 + 1.5 IQR. Marked, not
// dropped: the median is already robust to them, and a reader should see them.
std::vector<bool> tukeyOutliers(const std::vector<double>& values);

// A point estimate with a confidence interval.
struct Interval {
  double estimate = 0, low = 0, high = 0;
  // The interval's half width relative to the estimate (0.03: +-3%).
  double relativeHalfWidth() const;
};

inline constexpr int kBootstrapResamples = 2000;

// Percentile bootstrap interval (Efron & Tibshirani, ch. 13) of the median: the median of
// `resamples` resamples drawn with replacement; the interval is their (1-c)/2 and (1+c)/2
// quantiles. Deterministic for a seed (the same input gives the same interval).
Interval bootstrapMedian(const std::vector<double>& values, double confidence = 0.95,
                         int resamples = kBootstrapResamples, std::uint64_t seed = 1);

// Percentile bootstrap interval of median(num) / median(den). With `paired` (the samples were
// taken in rounds, num[i] and den[i] in one round, as round-robin interleaving does) the
// rounds are resampled together, so a drift of the machine shared by both cancels; otherwise
// each sample is resampled alone.
Interval bootstrapRatio(const std::vector<double>& num, const std::vector<double>& den, bool paired,
                        double confidence = 0.95, int resamples = kBootstrapResamples,
                        std::uint64_t seed = 1);

// "1.37 [1.30, 1.45]": an interval for printing.
std::string formatInterval(const Interval& i, int precision = 2);

// Whether an interval says a ratio is below / above `bound` with confidence: "holds" when the
// whole interval is on the claimed side, "fails" when the whole interval is on the other side,
// "undecided" when it contains the bound.
std::string orderingVerdict(const Interval& ratio, double bound, bool claimBelow);

// Change points in a series (history of a case's medians, oldest first), found by binary
// segmentation with Pettitt's rank statistic (Pettitt 1979, "A non-parametric approach to the
// change-point problem"): K = max_k |U_k|, U_k = sum_{i<=k<j} sign(x_j - x_i), the
// Mann-Whitney statistic of the split at k. Its p-value is a permutation test (the series
// shuffled `permutations` times, K recomputed: exact up to Monte-Carlo error, valid for any
// noise distribution and for the max over every split), so on a series without change the
// chance of reporting one is at most alpha. A segment that gives p < alpha is split there
// and both halves are searched again (each half by the same test).
struct ChangePoint {
  int index = 0;                 // the first value of the new segment
  double before = 0, after = 0;  // medians of the segments either side
  double size = 0;               // after / before - 1 (0.10: 10% larger)
  double p = 1;
};
struct ChangePointOptions {
  double alpha = 0.01;
  int permutations = 999;
  int minSegment = 2;  // values on each side of a split
  std::uint64_t seed = 1;
};
std::vector<ChangePoint> findChangePoints(const std::vector<double>& series,
                                          const ChangePointOptions& options = {});

}  // namespace sb
