#include "bench/cli/mann_whitney.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace ocpb {
namespace {

// Strata whose exact distributions would take more steps than this to build and convolve use the
// normal approximation of the sum (a fraction of a second of work at most).
constexpr double kMaxExactSteps = 5e7;

// Everything is counted in doubled units, so that mid-ranks of ties and U with its half counts
// are integers: D = 2U - n_base n_new, the centered doubled statistic (mean 0 under the null).
struct Stratum {
  int n_base = 0, n_new = 0;
  long long d = 0;                       // observed D
  double variance_u = 0.0;               // tie-corrected null variance of U
  std::vector<long long> doubled_ranks;  // of the pooled sample
};

std::vector<double> Finite(const std::vector<double>& v) {
  std::vector<double> out;
  for (double x : v) {
    if (std::isfinite(x)) out.push_back(x);
  }
  return out;
}

// The exact null distribution of D: every n_new-subset of the pooled doubled ranks is equally
// likely to be the new sample. counts[k][s]: subsets of size k of the ranks seen so far whose
// doubled ranks sum to s.
std::vector<double> ExactDistribution(const std::vector<long long>& doubled_ranks,
                                      int n_base,
                                      int n_new) {
  long long max_sum = 0;
  for (long long r : doubled_ranks) max_sum += r;
  std::vector<std::vector<double>> counts(n_new + 1, std::vector<double>(max_sum + 1, 0.0));
  counts[0][0] = 1.0;
  for (long long r : doubled_ranks) {
    for (int k = n_new; k >= 1; --k) {
      for (long long s = max_sum; s >= r; --s) counts[k][s] += counts[k - 1][s - r];
    }
  }
  double total = 0.0;
  for (double c : counts[n_new]) total += c;
  const long long nn = static_cast<long long>(n_base) * n_new;
  std::vector<double> p(2 * nn + 1, 0.0);
  const long long offset = static_cast<long long>(n_new) * (n_new + 1);  // 2 * min rank sum
  for (long long s = 0; s <= max_sum; ++s) {
    if (counts[n_new][s] == 0.0) continue;
    const long long d = s - offset - nn;  // 2U - n_base n_new
    p[d + nn] += counts[n_new][s] / total;
  }
  return p;
}

Stratum MakeStratum(const std::vector<double>& base_in, const std::vector<double>& new_in) {
  const std::vector<double> base = Finite(base_in), next = Finite(new_in);
  Stratum s;
  s.n_base = static_cast<int>(base.size());
  s.n_new = static_cast<int>(next.size());
  const int n = s.n_base + s.n_new;
  if (s.n_base == 0 || s.n_new == 0) return s;
  std::vector<std::pair<double, bool>> pooled;  // value, is new
  for (double x : base) pooled.push_back({x, false});
  for (double x : next) pooled.push_back({x, true});
  std::sort(pooled.begin(), pooled.end());
  std::vector<long long> doubled_ranks(n);
  long long new_sum = 0;
  double ties = 0.0;  // sum of t^3 - t over tie blocks
  for (int i = 0; i < n;) {
    int j = i;
    while (j < n && pooled[j].first == pooled[i].first) ++j;
    const long long doubled = (i + 1) + j;  // twice the mid-rank of positions i+1 .. j
    for (int k = i; k < j; ++k) {
      doubled_ranks[k] = doubled;
      if (pooled[k].second) new_sum += doubled;
    }
    const double t = j - i;
    ties += t * t * t - t;
    i = j;
  }
  const long long nn = static_cast<long long>(s.n_base) * s.n_new;
  s.d = new_sum - static_cast<long long>(s.n_new) * (s.n_new + 1) - nn;
  s.variance_u = n > 1 ? nn / 12.0 * ((n + 1) - ties / (static_cast<double>(n) * (n - 1))) : 0.0;
  s.doubled_ranks = std::move(doubled_ranks);
  return s;
}

// Two-sided: P(|D| >= |d|) from a distribution over D indexed from -half.
double TwoSidedP(const std::vector<double>& p_of_d, long long half, long long d) {
  double p = 0.0;
  for (long long k = -half; k <= half; ++k) {
    if (std::llabs(k) >= std::llabs(d)) p += p_of_d[k + half];
  }
  return std::min(1.0, p);
}

double NormalTwoSidedP(long long d, double variance_u) {
  if (!(variance_u > 0.0)) return 1.0;
  // |U - mean| = |D| / 2, less the continuity correction of 1/2.
  const double z = std::max(0.0, std::llabs(d) / 2.0 - 0.5) / std::sqrt(variance_u);
  return std::min(1.0, std::erfc(z / std::sqrt(2.0)));
}

RankTestResult Combine(const std::vector<Stratum>& strata) {
  RankTestResult r;
  long long d = 0, half = 0;
  double variance = 0.0, steps = 0.0;
  bool exact = true;
  for (const Stratum& s : strata) {
    if (s.n_base == 0 || s.n_new == 0) continue;
    const int n = s.n_base + s.n_new;
    const long long nn = static_cast<long long>(s.n_base) * s.n_new;
    r.n_base += s.n_base;
    r.n_new += s.n_new;
    r.mean_u += nn / 2.0;
    r.u += (s.d + nn) / 2.0;
    d += s.d;
    variance += s.variance_u;
    // The work of the stratum's exact distribution and of convolving it into the sum.
    steps += static_cast<double>(n) * s.n_new * n * (n + 1.0);
    steps += static_cast<double>(2 * half + 1) * static_cast<double>(2 * nn + 1);
    half += nn;
    exact = exact && n <= kExactRankTestLimit;
  }
  exact = exact && steps <= kMaxExactSteps;
  r.exact = exact;
  if (r.n_base == 0) return r;  // nothing to compare: p = 1
  if (!exact) {
    r.p_value = NormalTwoSidedP(d, variance);
    return r;
  }
  std::vector<double> total{1.0};  // the distribution of the sum so far, from -h to h
  long long h = 0;
  for (const Stratum& s : strata) {
    if (s.n_base == 0 || s.n_new == 0) continue;
    const std::vector<double> p_of_d = ExactDistribution(s.doubled_ranks, s.n_base, s.n_new);
    const long long nn = static_cast<long long>(s.n_base) * s.n_new;
    std::vector<double> next(2 * (h + nn) + 1, 0.0);
    for (size_t a = 0; a < total.size(); ++a) {
      if (total[a] == 0.0) continue;
      for (size_t b = 0; b < p_of_d.size(); ++b) next[a + b] += total[a] * p_of_d[b];
    }
    total = std::move(next);
    h += nn;
  }
  r.p_value = TwoSidedP(total, h, d);
  return r;
}

}  // namespace

RankTestResult MannWhitneyU(const std::vector<double>& base, const std::vector<double>& next) {
  return Combine({MakeStratum(base, next)});
}

RankTestResult StratifiedMannWhitneyU(
    const std::vector<std::pair<std::vector<double>, std::vector<double>>>& strata) {
  std::vector<Stratum> s;
  s.reserve(strata.size());
  for (const auto& [base, next] : strata) s.push_back(MakeStratum(base, next));
  return Combine(s);
}

double SmallestTwoSidedP(int n_base, int n_new) {
  if (n_base <= 0 || n_new <= 0) return 1.0;
  // log C(n, k) through lgamma: exact enough for a bound that is printed to two digits.
  const double log_c =
      std::lgamma(n_base + n_new + 1.0) - std::lgamma(n_base + 1.0) - std::lgamma(n_new + 1.0);
  return std::min(1.0, 2.0 * std::exp(-log_c));
}

}  // namespace ocpb
