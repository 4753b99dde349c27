#include "common/ground_motion.h"

#include <Eigen/Dense>
#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <complex>

namespace ddafem
{
std::vector<double> to_acceleration(const std::vector<double>& samples, double dt,
                                    MotionQuantity quantity)
{
  if (quantity == MotionQuantity::acceleration)
    return samples;
  const std::size_t n = samples.size();
  assert(n >= 3);
  // Central first differences inside, one-sided at the ends.
  const auto derivative = [n, dt](const std::vector<double>& x)
  {
    std::vector<double> d(n);
    d.front() = (x[1] - x[0]) / dt;
    d.back() = (x[n - 1] - x[n - 2]) / dt;
    for (std::size_t i = 1; i + 1 < n; ++i)
      d[i] = (x[i + 1] - x[i - 1]) / (2.0 * dt);
    return d;
  };
  if (quantity == MotionQuantity::velocity)
    return derivative(samples);
  // Displacement: second central differences, the end values repeated.
  std::vector<double> a(n);
  for (std::size_t i = 1; i + 1 < n; ++i)
    a[i] = (samples[i + 1] - 2.0 * samples[i] + samples[i - 1]) / (dt * dt);
  a.front() = a[1];
  a.back() = a[n - 2];
  return a;
}

std::vector<double> integrate(const std::vector<double>& x, double dt)
{
  std::vector<double> y(x.size(), 0.0);
  for (std::size_t i = 1; i < x.size(); ++i)
    y[i] = y[i - 1] + 0.5 * dt * (x[i - 1] + x[i]);
  return y;
}

void taper_ends(std::vector<double>& x, double dt, double seconds)
{
  if (seconds <= 0.0 || x.size() < 2)
    return;
  const std::size_t n = x.size();
  const std::size_t m = std::min(n / 2, static_cast<std::size_t>(std::ceil(seconds / dt)));
  for (std::size_t i = 0; i < m; ++i)
  {
    const double w = 0.5 * (1.0 - std::cos(M_PI * static_cast<double>(i) * dt / seconds));
    x[i] *= w;
    x[n - 1 - i] *= w;
  }
}

BaselineCorrection correct_baseline(std::vector<double>& a, double dt, int degree, double taper)
{
  assert(degree >= 2 && a.size() >= 2);
  const std::size_t n = a.size();
  const int m = degree - 1; // basis accelerations (t/T)^k, k = 0 .. degree - 2
  const double length = dt * static_cast<double>(n - 1);

  // Displacements and end velocities of the record and of each basis acceleration, by the same
  // trapezoidal rule twice, so that the constraint holds for the discrete motion exactly.
  const std::vector<double> v = integrate(a, dt);
  const std::vector<double> u = integrate(v, dt);
  Eigen::MatrixXd basis_u(n, m);
  Eigen::VectorXd basis_v_end(m);
  std::vector<std::vector<double>> basis(m, std::vector<double>(n));
  for (int k = 0; k < m; ++k)
  {
    std::vector<double>& phi = basis[k];
    for (std::size_t i = 0; i < n; ++i)
      phi[i] = std::pow(dt * static_cast<double>(i) / length, k);
    taper_ends(phi, dt, taper);
    const std::vector<double> phi_v = integrate(phi, dt);
    const std::vector<double> phi_u = integrate(phi_v, dt);
    basis_v_end(k) = phi_v.back();
    basis_u.col(k) = Eigen::Map<const Eigen::VectorXd>(phi_u.data(), static_cast<Eigen::Index>(n));
  }

  // min |u - B c|^2 subject to basis_v_end . c = v_end: the KKT system.
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(m + 1, m + 1);
  kkt.topLeftCorner(m, m) = basis_u.transpose() * basis_u;
  kkt.block(0, m, m, 1) = basis_v_end;
  kkt.block(m, 0, 1, m) = basis_v_end.transpose();
  Eigen::VectorXd rhs(m + 1);
  rhs.head(m) = basis_u.transpose() *
                Eigen::Map<const Eigen::VectorXd>(u.data(), static_cast<Eigen::Index>(n));
  rhs(m) = v.back();
  const Eigen::VectorXd solution = kkt.fullPivLu().solve(rhs);

  BaselineCorrection c;
  c.end_velocity_before = v.back();
  c.end_displacement_before = u.back();
  c.coefficients.assign(solution.data(), solution.data() + m);
  for (int k = 0; k < m; ++k)
    for (std::size_t i = 0; i < n; ++i)
      a[i] -= solution(k) * basis[k][i];
  c.end_displacement_after = integrate(integrate(a, dt), dt).back();
  return c;
}

double incident_factor(RecordMotion motion)
{
  return motion == RecordMotion::outcrop ? 0.5 : 1.0;
}

namespace
{
/// Peak absolute value.
double peak(const std::vector<double>& x)
{
  double p = 0.0;
  for (const double xi : x)
    p = std::max(p, std::abs(xi));
  return p;
}

/// Squared Fourier amplitudes C_j^2 of x at f_j = j / (N dt), j = 0 .. N / 2, x padded with
/// zeros to N = the next power of 2.
std::vector<double> power_spectrum(const std::vector<double>& x, std::size_t padded)
{
  std::vector<double> input(padded, 0.0);
  std::copy(x.begin(), x.end(), input.begin());
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spectrum;
  fft.fwd(spectrum, input);
  std::vector<double> power(padded / 2 + 1);
  for (std::size_t j = 0; j < power.size(); ++j)
    power[j] = std::norm(spectrum[j]);
  return power;
}
} // namespace

MotionSummary summarize_motion(const std::vector<double>& a, double dt)
{
  assert(a.size() >= 2);
  MotionSummary s;
  s.duration = dt * static_cast<double>(a.size() - 1);
  s.pga = peak(a);
  const std::vector<double> v = integrate(a, dt);
  s.pgv = peak(v);
  s.pgd = peak(integrate(v, dt));

  std::vector<double> a2(a.size());
  std::transform(a.begin(), a.end(), a2.begin(), [](double x) { return x * x; });
  const std::vector<double> husid = integrate(a2, dt);
  s.arias_intensity = M_PI / (2.0 * standard_gravity) * husid.back();
  const auto time_at = [&](double fraction)
  {
    const auto it = std::lower_bound(husid.begin(), husid.end(), fraction * husid.back());
    return dt * static_cast<double>(it - husid.begin());
  };
  s.t5 = time_at(0.05);
  s.t95 = time_at(0.95);

  std::size_t padded = 1;
  while (padded < a.size())
    padded *= 2;
  const std::vector<double> power = power_spectrum(a, padded);
  const double df = 1.0 / (static_cast<double>(padded) * dt);
  double sum = 0.0, weighted_period = 0.0, total = 0.0;
  for (std::size_t j = 1; j < power.size(); ++j)
  {
    const double f = df * static_cast<double>(j);
    total += power[j];
    if (f >= 0.25 && f <= 20.0)
    {
      sum += power[j];
      weighted_period += power[j] / f;
    }
  }
  s.mean_frequency = weighted_period > 0.0 ? sum / weighted_period : 0.0;
  double cumulative = 0.0;
  for (std::size_t j = 1; j < power.size() && total > 0.0; ++j)
  {
    cumulative += power[j];
    if (cumulative >= 0.99 * total)
    {
      s.f99 = df * static_cast<double>(j);
      break;
    }
  }
  return s;
}

} // namespace ddafem
