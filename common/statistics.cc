#include "common/statistics.h"

#include "common/format.h"
#include "common/input_error.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

namespace ddafem::statistics
{
double normal_cdf(const double x)
{
  return 0.5 * std::erfc(-x / std::sqrt(2.0));
}

double normal_quantile(const double p)
{
  assert(p > 0.0 && p < 1.0);
  // Acklam (2003), "An algorithm for computing the inverse normal cumulative distribution
  // function": rational approximations in the centre and in the tails (p < 0.02425).
  static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,
                                 -2.759285104469687e+02, 1.383577518672690e+02,
                                 -3.066479806614716e+01, 2.506628277459239e+00};
  static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02,
                                 -1.556989798598866e+02, 6.680131188771972e+01,
                                 -1.328068155288572e+01};
  static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01,
                                 -2.400758277161838e+00, -2.549732539343734e+00,
                                 4.374664141464968e+00,  2.938163982698783e+00};
  static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01,
                                 2.445134137142996e+00, 3.754408661907416e+00};
  const double p_low = 0.02425;
  double x = 0.0;
  if (p < p_low || p > 1.0 - p_low)
  {
    const double q = std::sqrt(-2.0 * std::log(p < p_low ? p : 1.0 - p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
    if (p > 1.0 - p_low)
      x = -x;
  }
  else
  {
    const double q = p - 0.5, r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
  }
  // One Halley step on e = Phi(x) - p (Acklam's refinement); Phi from erfc on the side of the
  // tail, so that e keeps its relative accuracy there.
  const double e = p < 0.5 ? normal_cdf(x) - p : (1.0 - p) - normal_cdf(-x);
  const double u = e * std::sqrt(2.0 * M_PI) * std::exp(0.5 * x * x);
  return x - u / (1.0 + 0.5 * x * u);
}

Interval wilson_interval(const std::size_t k, const std::size_t n, const double z)
{
  assert(k <= n);
  if (n == 0)
    return {0.0, 1.0};
  const double nn = static_cast<double>(n), p = static_cast<double>(k) / nn, z2 = z * z;
  const double centre = p + z2 / (2.0 * nn);
  const double half = z * std::sqrt(p * (1.0 - p) / nn + z2 / (4.0 * nn * nn));
  const double denominator = 1.0 + z2 / nn;
  // At k = 0 the lower end is 0 and at k = n the upper end 1, exactly (in floating point
  // (centre + half) / denominator gives 1 - 2e-16 at k = n = 48, below the p = 1 it bounds).
  return {k == 0 ? 0.0 : std::max(0.0, (centre - half) / denominator),
          k == n ? 1.0 : std::min(1.0, (centre + half) / denominator)};
}

double quantile(std::vector<double> sample, const double p)
{
  assert(!sample.empty() && p >= 0.0 && p <= 1.0);
  std::sort(sample.begin(), sample.end());
  const double h = (static_cast<double>(sample.size()) - 1.0) * p;
  const std::size_t i = std::min(static_cast<std::size_t>(std::floor(h)), sample.size() - 1);
  // (Equal neighbours returned as they are: two infinite ones would interpolate to NaN.)
  if (i + 1 >= sample.size() || sample[i + 1] == sample[i])
    return sample[i];
  return sample[i] + (h - static_cast<double>(i)) * (sample[i + 1] - sample[i]);
}

namespace
{
/// P(B <= r) for B ~ Binomial(n, 1/2), summed from the terms C(n, i) 2^-n in logarithms.
double binomial_half_cdf(const std::size_t n, const std::size_t r)
{
  double sum = 0.0;
  for (std::size_t i = 0; i <= r && i <= n; ++i)
    sum += std::exp(std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0) -
                    static_cast<double>(n) * std::log(2.0));
  return sum;
}
} // namespace

MedianInterval median_interval(std::vector<double> sample, const double confidence)
{
  MedianInterval m;
  const std::size_t n = sample.size();
  const double tail = 0.5 * (1.0 - confidence);
  // The largest r with P(B <= r - 1) <= tail; r <= n / 2 keeps x_(r) <= x_(n + 1 - r).
  for (std::size_t r = 1; r <= n / 2 && binomial_half_cdf(n, r - 1) <= tail; ++r)
    m.rank = r;
  if (m.rank == 0)
    return m;
  std::sort(sample.begin(), sample.end());
  m.interval = {sample[m.rank - 1], sample[n - m.rank]};
  m.coverage = 1.0 - 2.0 * binomial_half_cdf(n, m.rank - 1);
  m.available = true;
  return m;
}

SampleSummary summarize(const std::vector<double>& sample)
{
  SampleSummary s;
  s.n = sample.size();
  if (sample.empty())
    return s;
  s.q05 = quantile(sample, 0.05);
  s.median = quantile(sample, 0.5);
  s.q95 = quantile(sample, 0.95);
  s.median_interval = median_interval(sample);
  return s;
}

namespace
{
/// Phi(eta) and 1 - Phi(eta), each from erfc so that neither loses its tail.
std::pair<double, double> probabilities(const double eta)
{
  return {normal_cdf(eta), normal_cdf(-eta)};
}

/// The log-likelihood in the probit parameters: eta_j = a + b ln IM_j.
double probit_log_likelihood(const std::vector<FragilityLevel>& levels, const double a,
                             const double b)
{
  double sum = 0.0;
  for (const FragilityLevel& l : levels)
  {
    const auto [p, q] = probabilities(a + b * std::log(l.im));
    const double z = static_cast<double>(l.exceeded), rest = static_cast<double>(l.n) - z;
    // 0 ln 0 = 0: a level without exceedances does not ask p > 0.
    sum += (z > 0.0 ? z * std::log(p) : 0.0) + (rest > 0.0 ? rest * std::log(q) : 0.0);
  }
  return sum;
}

/// The starting point: least squares of Phi^-1 of the fractions, each kept within
/// [1/(2n_j), 1 - 1/(2n_j)], on ln IM. Returns (a, b).
std::array<double, 2> probit_start(const std::vector<FragilityLevel>& levels)
{
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0, m = 0.0;
  for (const FragilityLevel& l : levels)
  {
    if (l.n == 0)
      continue;
    const double n = static_cast<double>(l.n), half = 0.5 / n;
    const double f = std::clamp(static_cast<double>(l.exceeded) / n, half, 1.0 - half);
    const double x = std::log(l.im), y = normal_quantile(f);
    sx += x, sy += y, sxx += x * x, sxy += x * y, m += 1.0;
  }
  const double var = sxx - sx * sx / m;
  const double b = var > 0.0 ? (sxy - sx * sy / m) / var : 1.0;
  return {(sy - b * sx) / m, b};
}

/// Fisher scoring for (a, b): the expected information of level j is
/// n_j phi_j^2 / (p_j (1 - p_j)) [1, x_j; x_j, x_j^2], x_j = ln IM_j, and the score
/// sum_j (z_j - n_j p_j) phi_j / (p_j (1 - p_j)) [1, x_j]. Steps are halved until the
/// log-likelihood does not fall. Returns (a, b) at convergence.
std::array<double, 2> probit_maximum(const std::vector<FragilityLevel>& levels,
                                     std::array<double, 2> ab)
{
  double current = probit_log_likelihood(levels, ab[0], ab[1]);
  for (int iteration = 0; iteration < 500; ++iteration)
  {
    double i11 = 0.0, i12 = 0.0, i22 = 0.0, s1 = 0.0, s2 = 0.0;
    for (const FragilityLevel& l : levels)
    {
      const double x = std::log(l.im), eta = ab[0] + ab[1] * x;
      const auto [p, q] = probabilities(eta);
      const double pq = std::max(p * q, 1e-300);
      const double phi = std::exp(-0.5 * eta * eta) / std::sqrt(2.0 * M_PI);
      const double n = static_cast<double>(l.n), w = n * phi * phi / pq;
      const double score = (static_cast<double>(l.exceeded) - n * p) * phi / pq;
      i11 += w, i12 += w * x, i22 += w * x * x, s1 += score, s2 += score * x;
    }
    const double det = i11 * i22 - i12 * i12;
    if (!(det > 0.0))
      break;
    std::array<double, 2> step = {(i22 * s1 - i12 * s2) / det, (i11 * s2 - i12 * s1) / det};
    bool improved = false;
    for (int halving = 0; halving < 60 && !improved; ++halving)
    {
      const std::array<double, 2> trial = {ab[0] + step[0], ab[1] + step[1]};
      const double value = probit_log_likelihood(levels, trial[0], trial[1]);
      if (std::isfinite(value) && value >= current)
      {
        improved = true;
        ab = trial;
        current = value;
      }
      else
        step = {0.5 * step[0], 0.5 * step[1]};
    }
    const double size = std::hypot(step[0], step[1]) / (1.0 + std::hypot(ab[0], ab[1]));
    if (!improved || size < 1e-14)
      break;
  }
  return ab;
}
} // namespace

double fragility_log_likelihood(const std::vector<FragilityLevel>& levels, const double theta,
                                const double beta)
{
  return probit_log_likelihood(levels, -std::log(theta) / beta, 1.0 / beta);
}

namespace
{
/// How far the levels, sorted by intensity, read "first* partial? second*", where `first` is a
/// level whose count of exceedances is `first_count(level)`: returns whether the whole list
/// does, and the number of leading `first` levels and the index of the first `second` level.
struct StepPattern
{
  bool whole = false;
  std::size_t n_first = 0, second_begin = 0;
};

StepPattern step_pattern(const std::vector<FragilityLevel>& sorted, bool increasing)
{
  const auto first = [&](const FragilityLevel& l)
  { return increasing ? l.exceeded == 0 : l.exceeded == l.n; };
  const auto second = [&](const FragilityLevel& l)
  { return increasing ? l.exceeded == l.n : l.exceeded == 0; };
  StepPattern s;
  std::size_t i = 0;
  while (i < sorted.size() && first(sorted[i]))
    ++i;
  s.n_first = i;
  if (i < sorted.size() && !second(sorted[i]))
    ++i; // the one partial level allowed
  s.second_begin = i;
  while (i < sorted.size() && second(sorted[i]))
    ++i;
  s.whole = i == sorted.size();
  return s;
}
} // namespace

FragilityFit fit_lognormal_fragility(const std::vector<FragilityLevel>& levels)
{
  FragilityFit fit;
  std::vector<FragilityLevel> sorted;
  for (const FragilityLevel& l : levels)
    if (l.n > 0)
      sorted.push_back(l);
  std::sort(sorted.begin(), sorted.end(),
            [](const FragilityLevel& x, const FragilityLevel& y) { return x.im < y.im; });
  const std::size_t m = sorted.size();
  // (Quasi-)complete separation in the one regressor ln IM: the fractions step from 0 to 1 with
  // at most one level between; then the likelihood has no maximum and grows as beta -> 0
  // (Albert & Anderson 1984, Biometrika 71:1).
  const StepPattern up = step_pattern(sorted, true), down = step_pattern(sorted, false);
  if (up.whole)
  {
    if (up.n_first > 0)
      fit.highest_none = sorted[up.n_first - 1].im;
    if (up.second_begin < m)
      fit.lowest_all = sorted[up.second_begin].im;
  }
  if (m == 0 || (up.whole && up.second_begin == up.n_first && (up.n_first == 0 || up.n_first == m)))
    fit.status = FragilityFitStatus::one_sided; // nothing, or all none, or all all
  else if (m == 1)
    fit.status = FragilityFitStatus::single_level;
  else if (up.whole)
    fit.status = FragilityFitStatus::separated;
  else if (down.whole)
    fit.status = FragilityFitStatus::decreasing;
  if (fit.status != FragilityFitStatus::resolved)
  {
    fit.log_likelihood = 0.0; // the supremum: every level's fraction reproduced
    return fit;
  }
  const std::array<double, 2> ab = probit_maximum(sorted, probit_start(sorted));
  fit.log_likelihood = probit_log_likelihood(sorted, ab[0], ab[1]);
  if (!(ab[1] > 0.0))
  {
    fit.status = FragilityFitStatus::decreasing;
    return fit;
  }
  fit.beta = 1.0 / ab[1];
  fit.theta = std::exp(-ab[0] / ab[1]);
  return fit;
}

std::uint64_t mix_seed(const std::uint64_t a, const std::uint64_t b)
{
  // SplitMix64's finaliser on a + golden-ratio multiples of (b + 1).
  std::uint64_t z = a + 0x9e3779b97f4a7c15ULL * (b + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

namespace
{
/// A uniform in (0, 1) from the 53 high bits of one output: (k + 1/2) 2^-53, never 0 or 1.
double open_uniform(std::mt19937_64& engine)
{
  return (static_cast<double>(engine() >> 11) + 0.5) * 0x1.0p-53;
}
} // namespace

FragilityBounds bootstrap_fragility(const std::vector<FragilityLevel>& levels,
                                    const std::size_t n_resamples, const std::uint64_t seed,
                                    const double low_q, const double high_q)
{
  FragilityBounds bounds;
  bounds.n_resamples = n_resamples;
  std::mt19937_64 engine(mix_seed(seed, 0));
  std::vector<double> thetas, betas;
  for (std::size_t r = 0; r < n_resamples; ++r)
  {
    std::vector<FragilityLevel> resample = levels;
    for (FragilityLevel& l : resample)
    {
      // n_j members drawn with replacement; members 0 .. z_j - 1 are the exceedances.
      std::size_t exceeded = 0;
      for (std::size_t i = 0; i < l.n; ++i)
        exceeded +=
            static_cast<std::size_t>(open_uniform(engine) * static_cast<double>(l.n)) < l.exceeded
                ? 1
                : 0;
      l.exceeded = exceeded;
    }
    const FragilityFit fit = fit_lognormal_fragility(resample);
    if (fit.status != FragilityFitStatus::resolved)
    {
      ++bounds.n_unresolved;
      continue;
    }
    thetas.push_back(fit.theta);
    betas.push_back(fit.beta);
  }
  if (!thetas.empty())
  {
    bounds.theta = {quantile(thetas, low_q), quantile(thetas, high_q)};
    bounds.beta = {quantile(betas, low_q), quantile(betas, high_q)};
  }
  return bounds;
}

Interval Distribution::support() const
{
  const double inf = std::numeric_limits<double>::infinity();
  switch (kind)
  {
  case DistributionKind::normal:
    return {-inf, inf};
  case DistributionKind::lognormal:
    return {0.0, inf};
  case DistributionKind::uniform:
    return {parameters[0], parameters[1]};
  case DistributionKind::truncnormal:
    return {parameters[2], parameters[3]};
  }
  return {-inf, inf};
}

double Distribution::sample(const std::uint64_t seed, const std::uint64_t member) const
{
  std::mt19937_64 engine(mix_seed(seed, member));
  const double u = open_uniform(engine);
  const std::vector<double>& v = parameters;
  switch (kind)
  {
  case DistributionKind::normal:
    return v[0] + v[1] * normal_quantile(u);
  case DistributionKind::lognormal:
    return v[0] * std::exp(v[1] * normal_quantile(u));
  case DistributionKind::uniform:
    return v[0] + (v[1] - v[0]) * u;
  case DistributionKind::truncnormal:
  {
    // The inverse CDF of the normal restricted to [low, high]: u mapped into
    // [Phi(alpha), Phi(beta)], alpha, beta the standardised bounds.
    const double lo = normal_cdf((v[2] - v[0]) / v[1]), hi = normal_cdf((v[3] - v[0]) / v[1]);
    const double p = std::clamp(lo + u * (hi - lo), 1e-300, 1.0 - 1e-16);
    return std::clamp(v[0] + v[1] * normal_quantile(p), v[2], v[3]);
  }
  }
  return 0.0;
}

namespace
{
/// "name(p1, p2, ...)" split into the name and the parameter texts; nothing if not that shape.
bool split_call(const std::string& text, std::string& name, std::vector<std::string>& arguments)
{
  const std::size_t open = text.find('('), close = text.rfind(')');
  if (open == std::string::npos || close == std::string::npos || close < open ||
      text.find_first_not_of(" \t", close + 1) != std::string::npos)
    return false;
  const auto trim = [](const std::string& s)
  {
    const std::size_t b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  };
  name = trim(text.substr(0, open));
  std::stringstream inside(text.substr(open + 1, close - open - 1));
  for (std::string item; std::getline(inside, item, ',');)
    arguments.push_back(trim(item));
  return true;
}
} // namespace

Distribution parse_distribution(const std::string& text)
{
  const std::string expected_forms = "expected normal(mean,sd), lognormal(median,beta), "
                                     "uniform(low,high) or truncnormal(mean,sd,low,high)";
  const auto error = [&](const std::string& what)
  { return InputError("distribution '" + text + "': " + what); };
  std::string name;
  std::vector<std::string> arguments;
  if (!split_call(text, name, arguments))
    throw error(expected_forms);
  const std::optional<DistributionKind> kind = value_of<DistributionKind>(name);
  if (!kind)
    throw error("unknown distribution '" + name + "': " + expected_forms);
  Distribution d{*kind, {}, text};
  const std::size_t arity = *kind == DistributionKind::truncnormal ? 4 : 2;
  if (arguments.size() != arity)
    throw error("expected " + std::to_string(arity) + " parameters, found " +
                std::to_string(arguments.size()) + ": " + expected_forms);
  for (const std::string& a : arguments)
  {
    std::size_t used = 0;
    double value = 0.0;
    try
    {
      value = std::stod(a, &used);
    }
    catch (const std::exception&)
    {
      used = 0;
    }
    if (a.empty() || used != a.size() || !std::isfinite(value))
      throw error("parameter '" + a + "' is not a number");
    d.parameters.push_back(value);
  }
  const std::vector<double>& v = d.parameters;
  if ((*kind == DistributionKind::normal || *kind == DistributionKind::truncnormal) && !(v[1] > 0))
    throw error("expected a standard deviation sd > 0, found " + format_number(v[1]));
  if (*kind == DistributionKind::lognormal && !(v[0] > 0 && v[1] > 0))
    throw error("expected a median > 0 and beta > 0, found " + format_number(v[0]) + " and " +
                format_number(v[1]));
  if (*kind == DistributionKind::uniform && !(v[0] < v[1]))
    throw error("expected low < high, found " + format_number(v[0]) + " and " +
                format_number(v[1]));
  if (*kind == DistributionKind::truncnormal && !(v[2] < v[3]))
    throw error("expected low < high, found " + format_number(v[2]) + " and " +
                format_number(v[3]));
  return d;
}

} // namespace ddafem::statistics
