// Statistics of ensembles and fragility curves (issue 53): binomial proportions (Wilson),
// quantiles and the order-statistic interval of a median, the lognormal fragility curve by
// maximum likelihood with bootstrap bounds, and the sampling distributions of `ensemble --vary`.
// Pure functions, no state; every random draw is a function of (seed, member) and the same on
// every platform (std::mt19937_64's output is fixed by the standard; the normal deviates are by
// inverse CDF, not by std::normal_distribution, whose algorithm is implementation-defined).
#pragma once

#include "common/enum_names.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ddafem::statistics
{
/// A closed interval [low, high].
struct Interval
{
  double low = 0.0;
  double high = 0.0;
};

/// The standard normal CDF Phi(x) = erfc(-x / sqrt 2) / 2 (accurate in both tails).
double normal_cdf(double x);

/// The standard normal quantile Phi^-1(p), 0 < p < 1: Acklam's rational approximation (relative
/// error 1.15e-9) refined by one Halley step on erfc, which brings it to about 1e-15.
double normal_quantile(double p);

/// The Wilson score interval of a binomial proportion k / n (Wilson 1927;
/// docs/reference/benchmarks.md E): (p + z^2/2n -+ z sqrt(p(1-p)/n + z^2/4n^2)) / (1 + z^2/n), p =
/// k/n; z = 1.96 for 95 %. n = 0 gives [0, 1]. Requires k <= n.
Interval wilson_interval(std::size_t k, std::size_t n, double z = 1.96);

/// The p-quantile (0 <= p <= 1) of a sample, by linear interpolation between order statistics
/// (Hyndman & Fan 1996, definition 7; R's and numpy's default): h = (n-1) p, x_(floor h) +
/// (h - floor h)(x_(floor h + 1) - x_(floor h)) on the sorted sample, 0-based. Requires n > 0.
double quantile(std::vector<double> sample, double p);

/// A distribution-free confidence interval of a median from order statistics.
struct MedianInterval
{
  Interval interval;      ///< [x_(rank), x_(n + 1 - rank)] of the sorted sample, 1-based ranks
  std::size_t rank = 0;   ///< the lower rank; 0 when the sample is too small (then none)
  double coverage = 0.0;  ///< 1 - 2 P(B <= rank - 1), B ~ Binomial(n, 1/2): >= the confidence
  bool available = false; ///< false if n is too small for the confidence (n < 6 for 95 %)
};

/// The interval of the median of a continuous distribution from its sample (e.g. Conover 1999,
/// Practical Nonparametric Statistics, 3.2): x_(r) <= median <= x_(n+1-r) with probability
/// 1 - 2 P(B <= r - 1), B ~ Binomial(n, 1/2). The rank r is the largest with
/// P(B <= r - 1) <= (1 - confidence) / 2. Example: n = 10, 95 %: r = 2, coverage 1 - 22/1024.
MedianInterval median_interval(std::vector<double> sample, double confidence = 0.95);

/// The 5 %, 50 % and 95 % quantiles of a sample and the 95 % interval of its median.
struct SampleSummary
{
  std::size_t n = 0;
  double q05 = 0.0, median = 0.0, q95 = 0.0;
  MedianInterval median_interval;
};

/// The summary of a sample; n = 0 gives zeros and no interval.
SampleSummary summarize(const std::vector<double>& sample);

/// One intensity level of a fragility analysis: n runs at intensity `im` (> 0, any unit), of which
/// `exceeded` reached the damage state.
struct FragilityLevel
{
  double im = 0.0;
  std::size_t n = 0;
  std::size_t exceeded = 0;
};

/// What the data allow of a lognormal fragility curve.
enum class FragilityFitStatus
{
  resolved,     ///< a maximum of the likelihood with 0 < beta < infinity
  separated,    ///< the fractions step from 0 to 1 (at most one level between): beta -> 0
  one_sided,    ///< no level has exceedances, or every level has only exceedances (or no level)
  single_level, ///< one level with some exceedances: two parameters from one fraction
  decreasing    ///< the fractions fall with the intensity: the best probit slope is <= 0
};

constexpr std::array<EnumName<FragilityFitStatus>, 5> enum_names(FragilityFitStatus)
{
  return {{{FragilityFitStatus::resolved, "resolved"},
           {FragilityFitStatus::separated, "separated"},
           {FragilityFitStatus::one_sided, "one_sided"},
           {FragilityFitStatus::single_level, "single_level"},
           {FragilityFitStatus::decreasing, "decreasing"}}};
}

/// A lognormal fragility curve P(DS | IM) = Phi(ln(IM / theta) / beta).
struct FragilityFit
{
  FragilityFitStatus status = FragilityFitStatus::resolved;
  double theta = 0.0;          ///< median [unit of IM]; resolved only
  double beta = 0.0;           ///< logarithmic standard deviation [-]; resolved only
  double log_likelihood = 0.0; ///< sum_j [z_j ln p_j + (n_j - z_j) ln(1 - p_j)] at the fit
  /// Separated or one-sided: the highest level with no exceedance and the lowest with only
  /// exceedances (theta lies between them; a side is absent if no level is of that kind).
  std::optional<double> highest_none, lowest_all;
};

/// The log-likelihood sum_j [z_j ln p_j + (n_j - z_j) ln(1 - p_j)], p_j = Phi(ln(IM_j/theta)/beta)
/// (Baker 2015, Earthquake Spectra 31(1):579, eq. 11 without the constant ln C(n_j, z_j)).
double fragility_log_likelihood(const std::vector<FragilityLevel>& levels, double theta,
                                double beta);

/// The maximum-likelihood lognormal fragility curve (Baker 2015). With a = -ln(theta)/beta and
/// b = 1/beta it is a binomial regression with a probit link on ln IM, whose log-likelihood is
/// concave in (a, b) (Pratt 1981, JASA 76:103): Fisher scoring with step halving from a
/// least-squares probit fit of the observed fractions converges to the one maximum. Perfect
/// separation (fractions 0 below, 1 above, at most one level between) has no maximum (the
/// likelihood grows as beta -> 0): the status says so with the bracket.
FragilityFit fit_lognormal_fragility(const std::vector<FragilityLevel>& levels);

/// Bootstrap bounds of a fragility fit.
struct FragilityBounds
{
  Interval theta, beta;         ///< quantiles (low_q, high_q) over the resolved resamples
  std::size_t n_resamples = 0;  ///< resamples drawn
  std::size_t n_unresolved = 0; ///< resamples without a resolved fit (left out of the bounds)
};

/// Bootstrap bounds of theta and beta (Efron & Tibshirani 1993, percentile method): each
/// resample draws n_j members with replacement within each level j (the count of exceedances
/// is then Binomial(n_j, z_j/n_j)), refits, and the bounds are the low_q and high_q quantiles of
/// the resolved fits. Deterministic in `seed`.
FragilityBounds bootstrap_fragility(const std::vector<FragilityLevel>& levels,
                                    std::size_t n_resamples = 1000, std::uint64_t seed = 1,
                                    double low_q = 0.05, double high_q = 0.95);

/// A seed derived from two integers by SplitMix64's finaliser (Steele, Lea & Flood 2014): distinct
/// pairs give unrelated streams. Used for member k's seeds and for each key's draws.
std::uint64_t mix_seed(std::uint64_t a, std::uint64_t b);

/// The kinds of `--vary` distributions.
enum class DistributionKind
{
  normal,     ///< normal(mean, sd)
  lognormal,  ///< lognormal(median, beta): ln X ~ normal(ln median, beta)
  uniform,    ///< uniform(low, high)
  truncnormal ///< truncnormal(mean, sd, low, high): normal(mean, sd) restricted to [low, high]
};

constexpr std::array<EnumName<DistributionKind>, 4> enum_names(DistributionKind)
{
  return {{{DistributionKind::normal, "normal"},
           {DistributionKind::lognormal, "lognormal"},
           {DistributionKind::uniform, "uniform"},
           {DistributionKind::truncnormal, "truncnormal"}}};
}

/// A distribution to sample a numeric scene key from, in the key's own unit.
struct Distribution
{
  DistributionKind kind = DistributionKind::normal;
  std::vector<double> parameters; ///< as written, in the order of the kind's comment
  std::string text;               ///< as written, e.g. "normal(35, 2)"

  /// The values it can take: [-inf, inf] for normal, [0, inf] for lognormal (open at 0).
  Interval support() const;
  /// Member `member`'s draw for `seed`: the inverse CDF of a uniform made from the 53 high bits
  /// of the first output of std::mt19937_64 seeded with mix_seed(seed, member).
  double sample(std::uint64_t seed, std::uint64_t member) const;
};

/// Parses "normal(mean,sd)", "lognormal(median,beta)", "uniform(low,high)" or
/// "truncnormal(mean,sd,low,high)" (spaces allowed). Throws InputError naming the text and what
/// was expected for an unknown name, a wrong number of parameters, a number that does not parse,
/// a spread (sd, beta) <= 0, a median <= 0, or low >= high.
Distribution parse_distribution(const std::string& text);

} // namespace ddafem::statistics
