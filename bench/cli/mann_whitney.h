// The Mann-Whitney U test (Wilcoxon rank-sum test) of two independent samples, and its
// stratified form over several pairs of samples: the confidence statement of `ocpbench compare`
// about CPU times from a case's timing repeats.
//
// Why a rank test: CPU times on a shared machine have a long right tail (a repeat that lands on a
// busy moment is much slower, never much faster), so a mean and a t interval are pulled by single
// outliers; ranks are not. Why exact: with the few repeats a suite takes (1, 3, 5) the normal
// approximation is far off in the tail, and the exact permutation distribution is cheap.
//
// Under the null hypothesis (both samples from one distribution) every assignment of the pooled
// values to the two sides is equally likely. U counts the pairs (base, new) with new > base (ties
// count 1/2); its two-sided p-value is the probability of a U at least as far from its mean
// n_base n_new / 2 as the observed one. The smallest p-value a pair of sample sizes can give is
// 2 / C(n_base + n_new, n_base): 1 for 1 vs 1 repeats (no statement possible), 0.1 for 3 vs 3 (a
// single case can never be significant at 0.05), 0.029 for 4 vs 4, 0.0079 for 5 vs 5.
#pragma once

#include <utility>
#include <vector>

namespace ocpb {

/// A rank test's outcome. `u` is the statistic of the new sample (pairs with new > base, ties
/// 1/2), `mean_u` its expectation under the null; p_value is two-sided.
struct RankTestResult {
  double u = 0.0;
  double mean_u = 0.0;
  double p_value = 1.0;
  bool exact = true;          ///< the exact permutation distribution (false: normal approximation)
  int n_base = 0, n_new = 0;  ///< sample sizes (summed over strata)
};

/// Pooled sizes n_base + n_new up to this get the exact distribution (ties included); larger
/// samples the normal approximation with tie correction and continuity correction.
inline constexpr int kExactRankTestLimit = 60;

/// The two-sided Mann-Whitney U test of `next` against `base`. NaN values are dropped; an empty
/// side gives p = 1 with n = 0.
RankTestResult MannWhitneyU(const std::vector<double>& base, const std::vector<double>& next);

/// The stratified test over pairs (base, new) of samples (one pair per case): the sum of the
/// strata's U against the convolution of their exact null distributions (each stratum permuted
/// within itself, so that cases of different speeds are never ranked against each other), or the
/// normal approximation of the sum when the exact convolution is too large. With one value per
/// side in every stratum it is the two-sided sign test over the strata.
RankTestResult StratifiedMannWhitneyU(
    const std::vector<std::pair<std::vector<double>, std::vector<double>>>& strata);

/// 2 / C(n_base + n_new, n_base), at most 1: the smallest two-sided p-value of the exact test
/// for these sample sizes (reached when the samples do not overlap).
double SmallestTwoSidedP(int n_base, int n_new);

}  // namespace ocpb
