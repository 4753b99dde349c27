// The statistics of ensembles and fragility curves (common/statistics.h) against closed forms:
// Wilson intervals worked by hand, quantiles and the order-statistic interval of a median from
// binomial sums, the maximum-likelihood fragility curve against the exact parameters and a brute
// force maximiser, and the sampling distributions' moments within three standard errors.
#include "common/statistics.h"

#include "common/input_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace
{
using namespace ddafem::statistics;

TEST(Statistics, NormalQuantileInvertsTheCdf)
{
  // Phi^-1(0.975) = 1.959963984540054 (to 16 digits, e.g. Abramowitz & Stegun 26.2 tables);
  // Phi^-1(0.5) = 0; the tails by the CDF itself: Phi(Phi^-1(p)) = p within 1e-14 relative.
  EXPECT_NEAR(normal_quantile(0.975), 1.959963984540054, 1e-14);
  EXPECT_NEAR(normal_quantile(0.025), -1.959963984540054, 1e-14);
  EXPECT_NEAR(normal_quantile(0.5), 0.0, 1e-15);
  for (const double p : {1e-12, 1e-6, 0.01, 0.02425, 0.3, 0.9, 0.99, 1.0 - 1e-9})
    EXPECT_NEAR(normal_cdf(normal_quantile(p)) / p, 1.0, 1e-12) << p;
}

TEST(Statistics, WilsonIntervalAgainstHandValues)
{
  // z = 1.96, n = 10: z^2/n = 0.38416, 1 + z^2/n = 1.38416, z^2/2n = 0.19208, z^2/4n^2 = 0.009604.
  // k = 0: p = 0, (0.19208 -+ 1.96 sqrt(0.009604)) / 1.38416 = (0.19208 -+ 0.19208) / 1.38416
  //   = [0, 0.38416 / 1.38416] = [0, 0.2775401688].
  // k = 5: p = 0.5, (0.69208 -+ 1.96 sqrt(0.025 + 0.009604)) / 1.38416
  //   = 0.5 -+ 0.3646021481 / 1.38416 = [0.2365895936, 0.7634104064].
  // k = 10: (1.19208 -+ 0.19208) / 1.38416 = [1 / 1.38416, 1] = [0.7224598312, 1].
  // Tolerance 1e-10: the hand values are rounded at the 10th decimal.
  const Interval a = wilson_interval(0, 10), b = wilson_interval(5, 10),
                 c = wilson_interval(10, 10);
  EXPECT_EQ(a.low, 0.0);
  EXPECT_NEAR(a.high, 0.2775401688, 1e-10);
  EXPECT_NEAR(b.low, 0.2365895936, 1e-10);
  EXPECT_NEAR(b.high, 0.7634104064, 1e-10);
  EXPECT_NEAR(c.low, 0.7224598312, 1e-10);
  EXPECT_EQ(c.high, 1.0);
  // k = 3, n = 32: p = 0.09375, centre 0.153775, half 1.96 sqrt(p(1-p)/32 + 0.00093789...)
  // = 0.1174843018, over 1.12005: [0.0324009626, 0.2421849934].
  const Interval d = wilson_interval(3, 32);
  EXPECT_NEAR(d.low, 0.0324009626, 1e-10);
  EXPECT_NEAR(d.high, 0.2421849934, 1e-10);
  // The ends exactly 0 and 1 at every n (the formula's rounding gave 1 - 2e-16 at k = n = 48,
  // so that p = 1 lay outside its own interval).
  for (std::size_t n = 1; n <= 200; ++n)
  {
    EXPECT_EQ(wilson_interval(0, n).low, 0.0) << n;
    EXPECT_EQ(wilson_interval(n, n).high, 1.0) << n;
  }
  const Interval none = wilson_interval(0, 0);
  EXPECT_EQ(none.low, 0.0);
  EXPECT_EQ(none.high, 1.0);
}

TEST(Statistics, QuantilesInterpolateOrderStatistics)
{
  // 1..11 unsorted: h = 10 p; the 5 % quantile is x_0 + 0.5 (x_1 - x_0) = 1.5, the median 6, the
  // 95 % 10.5. Exact in binary floating point.
  const std::vector<double> x = {7, 3, 11, 1, 5, 9, 2, 8, 4, 10, 6};
  EXPECT_EQ(quantile(x, 0.05), 1.5);
  EXPECT_EQ(quantile(x, 0.5), 6.0);
  EXPECT_EQ(quantile(x, 0.95), 10.5);
  EXPECT_EQ(quantile(x, 0.0), 1.0);
  EXPECT_EQ(quantile(x, 1.0), 11.0);
  EXPECT_EQ(quantile({4.0}, 0.3), 4.0);
  // Bootstrap fits that run off to an infinite median: a quantile between two of them is
  // infinite, not inf - inf = NaN (the default tunnel's fragility bound printed "-nan").
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(quantile({1.0, 2.0, inf, inf}, 0.95), inf);
  EXPECT_EQ(quantile({1.0, 2.0, inf, inf}, 0.5), inf); // between 2 and inf: inf, not NaN
  EXPECT_EQ(quantile({1.0, 2.0, inf, inf}, 0.25), 1.75);
  const SampleSummary s = summarize(x);
  EXPECT_EQ(s.n, 11u);
  EXPECT_EQ(s.median, 6.0);
  EXPECT_EQ(s.q05, 1.5);
}

TEST(Statistics, MedianIntervalByOrderStatistics)
{
  // n = 10, B ~ Binomial(10, 1/2): P(B <= 1) = 11/1024 = 0.0107 <= 0.025 < P(B <= 2) = 56/1024,
  // so r = 2: [x_(2), x_(9)] with coverage 1 - 22/1024.
  std::vector<double> x = {10, 1, 9, 2, 8, 3, 7, 4, 6, 5};
  MedianInterval m = median_interval(x);
  ASSERT_TRUE(m.available);
  EXPECT_EQ(m.rank, 2u);
  EXPECT_EQ(m.interval.low, 2.0);
  EXPECT_EQ(m.interval.high, 9.0);
  EXPECT_NEAR(m.coverage, 1.0 - 22.0 / 1024.0, 1e-14);
  // n = 6: P(B <= 0) = 1/64 <= 0.025 < P(B <= 1) = 7/64: r = 1, the range, coverage 62/64.
  m = median_interval({3, 1, 4, 1.5, 9, 2.6});
  ASSERT_TRUE(m.available);
  EXPECT_EQ(m.rank, 1u);
  EXPECT_EQ(m.interval.low, 1.0);
  EXPECT_EQ(m.interval.high, 9.0);
  EXPECT_NEAR(m.coverage, 62.0 / 64.0, 1e-14);
  // n = 5: P(B <= 0) = 1/32 > 0.025: no 95 % interval from 5 values.
  EXPECT_FALSE(median_interval({1, 2, 3, 4, 5}).available);
  // n = 32: P(B <= 9) = 0.01003 <= 0.025 < P(B <= 10) = 0.02508 (sums of C(32, i) / 2^32):
  // r = 10, [x_(10), x_(23)].
  std::vector<double> y;
  for (int i = 1; i <= 32; ++i)
    y.push_back(i);
  m = median_interval(y);
  EXPECT_EQ(m.rank, 10u);
  EXPECT_EQ(m.interval.low, 10.0);
  EXPECT_EQ(m.interval.high, 23.0);
}

/// Levels whose fractions are exactly Phi(ln(IM/theta)/beta) of n runs (n large, counts real).
std::vector<FragilityLevel> exact_levels(double theta, double beta, std::size_t n)
{
  std::vector<FragilityLevel> levels;
  for (const double im : {0.4, 0.6, 0.8, 1.0, 1.3, 1.7})
  {
    const double p = normal_cdf(std::log(im / theta) / beta);
    levels.push_back({im, n, static_cast<std::size_t>(std::llround(p * static_cast<double>(n)))});
  }
  return levels;
}

TEST(Statistics, FragilityRecoversExactParameters)
{
  // With n = 10^12 runs per level the counts carry the fractions to 1e-12, so the maximum of
  // the likelihood (where the fitted fractions equal the observed) is theta, beta within ~1e-10;
  // 1e-6 leaves room for the scoring's stopping rule.
  for (const auto& [theta, beta] : {std::pair{0.9, 0.35}, std::pair{0.62, 0.6}})
  {
    const FragilityFit fit = fit_lognormal_fragility(exact_levels(theta, beta, 1000000000000));
    ASSERT_EQ(fit.status, FragilityFitStatus::resolved);
    EXPECT_NEAR(fit.theta, theta, 1e-6);
    EXPECT_NEAR(fit.beta, beta, 1e-6);
  }
}

TEST(Statistics, FragilityAgreesWithBruteForceMaximum)
{
  // An irregular data set (non-monotonic fractions, unequal n): the fit's log-likelihood is at
  // least the best of a fine grid over (theta, beta), and its parameters are within two grid
  // steps of the grid's best (the likelihood is smooth and has one maximum).
  const std::vector<FragilityLevel> levels = {{0.3, 12, 1}, {0.5, 16, 2},  {0.7, 16, 7},
                                              {0.9, 10, 4}, {1.2, 16, 13}, {2.0, 8, 7}};
  const FragilityFit fit = fit_lognormal_fragility(levels);
  ASSERT_EQ(fit.status, FragilityFitStatus::resolved);
  double best = -1e300, best_theta = 0.0, best_beta = 0.0;
  const double d_ln_theta = 0.002, d_ln_beta = 0.002;
  for (double lt = std::log(0.3); lt < std::log(2.0); lt += d_ln_theta)
    for (double lb = std::log(0.1); lb < std::log(3.0); lb += d_ln_beta)
    {
      const double l = fragility_log_likelihood(levels, std::exp(lt), std::exp(lb));
      if (l > best)
        best = l, best_theta = std::exp(lt), best_beta = std::exp(lb);
    }
  EXPECT_GE(fit.log_likelihood, best - 1e-12);
  EXPECT_NEAR(std::log(fit.theta), std::log(best_theta), 2 * d_ln_theta);
  EXPECT_NEAR(std::log(fit.beta), std::log(best_beta), 2 * d_ln_beta);
  EXPECT_NEAR(fit.log_likelihood, fragility_log_likelihood(levels, fit.theta, fit.beta), 1e-12);
}

TEST(Statistics, FragilitySeparationIsDetected)
{
  // 0, 0, all, all: separated between 0.8 and 1.2.
  FragilityFit fit = fit_lognormal_fragility({{0.5, 8, 0}, {0.8, 8, 0}, {1.2, 8, 8}, {2, 8, 8}});
  EXPECT_EQ(fit.status, FragilityFitStatus::separated);
  EXPECT_EQ(fit.highest_none.value(), 0.8);
  EXPECT_EQ(fit.lowest_all.value(), 1.2);
  // One partial level between (quasi-complete separation): still no maximum.
  fit = fit_lognormal_fragility({{0.5, 8, 0}, {1.0, 8, 3}, {2, 8, 8}});
  EXPECT_EQ(fit.status, FragilityFitStatus::separated);
  EXPECT_EQ(fit.highest_none.value(), 0.5);
  EXPECT_EQ(fit.lowest_all.value(), 2.0);
  // Two partial levels: a maximum exists.
  EXPECT_EQ(fit_lognormal_fragility({{0.5, 8, 0}, {1.0, 8, 3}, {1.5, 8, 6}, {2, 8, 8}}).status,
            FragilityFitStatus::resolved);
  // Nothing exceeded anywhere / everything everywhere / falling fractions.
  fit = fit_lognormal_fragility({{0.5, 8, 0}, {1.0, 8, 0}});
  EXPECT_EQ(fit.status, FragilityFitStatus::one_sided);
  EXPECT_EQ(fit.highest_none.value(), 1.0);
  EXPECT_FALSE(fit.lowest_all);
  EXPECT_EQ(fit_lognormal_fragility({{0.5, 8, 8}, {1.0, 8, 8}}).status,
            FragilityFitStatus::one_sided);
  EXPECT_EQ(fit_lognormal_fragility({{0.5, 8, 8}, {1.0, 8, 0}}).status,
            FragilityFitStatus::decreasing);
  EXPECT_EQ(fit_lognormal_fragility({{0.5, 8, 3}}).status, FragilityFitStatus::single_level);
}

TEST(Statistics, FragilityBootstrapIsDeterministicAndBracketsTheFit)
{
  const std::vector<FragilityLevel> levels = {{0.4, 16, 1},  {0.6, 16, 4},  {0.8, 16, 8},
                                              {1.0, 16, 11}, {1.3, 16, 14}, {1.7, 16, 16}};
  const FragilityFit fit = fit_lognormal_fragility(levels);
  const FragilityBounds a = bootstrap_fragility(levels, 400, 7),
                        b = bootstrap_fragility(levels, 400, 7);
  EXPECT_EQ(a.theta.low, b.theta.low);
  EXPECT_EQ(a.beta.high, b.beta.high);
  EXPECT_EQ(a.n_resamples, 400u);
  EXPECT_LT(a.n_unresolved, 40u); // separation needs every level at 0 or 16 but one: rare
  EXPECT_LT(a.theta.low, fit.theta);
  EXPECT_GT(a.theta.high, fit.theta);
  EXPECT_LT(a.beta.low, fit.beta);
  EXPECT_GT(a.beta.high, fit.beta);
  // The 90 % band of theta is about 2 x 1.645 x its standard error, beta theta / sqrt(sum of
  // information) ~ 0.05-0.1 here: wider than 0.02, narrower than 0.5.
  EXPECT_GT(a.theta.high - a.theta.low, 0.02);
  EXPECT_LT(a.theta.high - a.theta.low, 0.5);
}

/// Mean and standard deviation of 20000 draws of `d` with seed 11.
std::pair<double, double> moments(const Distribution& d, std::size_t n = 20000)
{
  double sum = 0.0, sum2 = 0.0;
  for (std::size_t k = 0; k < n; ++k)
  {
    const double x = d.sample(11, k);
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / n;
  return {mean, std::sqrt((sum2 / n - mean * mean) * n / (n - 1))};
}

TEST(Statistics, DistributionsHaveTheirMoments)
{
  // Three standard errors: of the mean sd/sqrt(n), of the sd about sd/sqrt(2n) for a normal
  // (for the others, sqrt((mu4/sd^4 - 1)/(4n)) sd: 1.8/sqrt(4n) for the uniform's kurtosis 1.8).
  const double n = 20000;
  {
    const auto [mean, sd] = moments(parse_distribution("normal(35, 2)"));
    EXPECT_NEAR(mean, 35.0, 3 * 2 / std::sqrt(n));
    EXPECT_NEAR(sd, 2.0, 3 * 2 / std::sqrt(2 * n));
  }
  {
    // uniform(1, 3): mean 2, sd 2/sqrt(12); (mu4/sd^4 - 1) = 0.8.
    const auto [mean, sd] = moments(parse_distribution("uniform(1,3)"));
    const double s = 2.0 / std::sqrt(12.0);
    EXPECT_NEAR(mean, 2.0, 3 * s / std::sqrt(n));
    EXPECT_NEAR(sd, s, 3 * s * std::sqrt(0.8 / (4 * n)));
  }
  {
    // lognormal(2, 0.3): ln X normal(ln 2, 0.3), checked on the logarithms.
    const Distribution d = parse_distribution("lognormal( 2 , 0.3 )");
    double sum = 0.0, sum2 = 0.0;
    for (std::size_t k = 0; k < n; ++k)
    {
      const double l = std::log(d.sample(5, k));
      sum += l, sum2 += l * l;
    }
    const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
    EXPECT_NEAR(mean, std::log(2.0), 3 * 0.3 / std::sqrt(n));
    EXPECT_NEAR(sd, 0.3, 3 * 0.3 / std::sqrt(2 * n));
  }
  {
    // truncnormal(0, 1, -1, 1): mean 0 by symmetry, variance 1 - 2 phi(1)/(2 Phi(1) - 1)
    // = 1 - 2 x 0.2419707245 / 0.6826894921 = 0.2911142467; stays within [-1, 1].
    const Distribution d = parse_distribution("truncnormal(0,1,-1,1)");
    const auto [mean, sd] = moments(d);
    const double s = std::sqrt(0.2911142467);
    EXPECT_NEAR(mean, 0.0, 3 * s / std::sqrt(n));
    EXPECT_NEAR(sd, s, 3 * s * std::sqrt(1.0 / (4 * n))); // kurtosis < 3 here: (mu4/s^4-1) < 1
    for (std::size_t k = 0; k < 20000; ++k)
    {
      const double x = d.sample(3, k);
      ASSERT_GE(x, -1.0);
      ASSERT_LE(x, 1.0);
    }
    EXPECT_EQ(d.support().low, -1.0);
    EXPECT_EQ(d.support().high, 1.0);
  }
}

TEST(Statistics, SamplesAreAFunctionOfSeedAndMember)
{
  const Distribution d = parse_distribution("normal(0,1)");
  EXPECT_EQ(d.sample(1, 4), d.sample(1, 4));
  EXPECT_NE(d.sample(1, 4), d.sample(1, 5));
  EXPECT_NE(d.sample(1, 4), d.sample(2, 4));
  EXPECT_NE(mix_seed(1, 2), mix_seed(2, 1));
}

TEST(Statistics, BadDistributionTextsThrowNamingThem)
{
  const auto message = [](const std::string& text)
  {
    try
    {
      parse_distribution(text);
    }
    catch (const ddafem::InputError& e)
    {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("gauss(1,2)").find("unknown distribution 'gauss'"), std::string::npos);
  EXPECT_NE(message("normal(1)").find("expected 2 parameters, found 1"), std::string::npos);
  EXPECT_NE(message("truncnormal(1,2,3)").find("expected 4 parameters"), std::string::npos);
  EXPECT_NE(message("normal(1,-2)").find("sd > 0, found -2"), std::string::npos);
  EXPECT_NE(message("lognormal(1,-0.1)").find("beta > 0"), std::string::npos);
  EXPECT_NE(message("lognormal(0,0.1)").find("median > 0"), std::string::npos);
  EXPECT_NE(message("uniform(3,1)").find("low < high, found 3 and 1"), std::string::npos);
  EXPECT_NE(message("truncnormal(0,1,2,2)").find("low < high"), std::string::npos);
  EXPECT_NE(message("normal(a,1)").find("parameter 'a' is not a number"), std::string::npos);
  EXPECT_NE(message("normal 1 2").find("expected normal(mean,sd)"), std::string::npos);
  EXPECT_NE(message("normal(1,2").find("'normal(1,2'"), std::string::npos);
  EXPECT_EQ(message("uniform(1, 2)"), "no error");
}
} // namespace
