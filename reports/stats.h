// Summary statistics over repetitions (median, min, max, mean, standard deviation) and the
// rank test that `compare-runs` uses to judge whether a change is more than noise.
#pragma once

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

}  // namespace sb
