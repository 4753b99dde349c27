// FE measurement of Lysmer reflection coefficients (see lysmer_measurement.h).
#include "fem/lysmer_measurement.h"

#include "fem/elastic_wave_model.h"

#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace ddafem::fem
{
namespace
{
constexpr double density = 2000.0;
constexpr double vs = 1000.0;
const double vp = std::sqrt(3.0) * vs; // nu = 0.25, plane strain
constexpr double amplitude = 1e-3;     // [m]

/// Derivative of the Ricker wavelet A (1 - 2 a t^2) exp(-a t^2), a = (pi f0)^2.
double ricker_rate(const double t, const double f0)
{
  const double a = M_PI * M_PI * f0 * f0;
  return amplitude * std::exp(-a * t * t) * (-6.0 * a * t + 4.0 * a * a * t * t * t);
}

double ricker(const double t, const double f0)
{
  const double a = M_PI * M_PI * f0 * f0;
  return amplitude * (1.0 - 2.0 * a * t * t) * std::exp(-a * t * t);
}

/// Hilbert transform of ricker_rate: (1/pi) int_0^inf (g(t - u) - g(t + u)) / u du.
double ricker_rate_hilbert(const double t, const double f0)
{
  const double du = 1.0 / (f0 * 400.0);
  const double end = std::abs(t) + 3.0 / f0;
  double sum = 0.0;
  for (double u = 0.5 * du; u < end; u += du)
    sum += (ricker_rate(t - u, f0) - ricker_rate(t + u, f0)) / u;
  return sum * du / M_PI;
}

/// Solves the small dense system A x = b (Gaussian elimination with partial pivoting).
std::vector<double> solve_dense(std::vector<std::vector<double>> A, std::vector<double> b)
{
  const std::size_t n = b.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    std::size_t pivot = k;
    for (std::size_t i = k + 1; i < n; ++i)
      if (std::abs(A[i][k]) > std::abs(A[pivot][k]))
        pivot = i;
    std::swap(A[k], A[pivot]);
    std::swap(b[k], b[pivot]);
    for (std::size_t i = k + 1; i < n; ++i)
    {
      const double f = A[i][k] / A[k][k];
      for (std::size_t j = k; j < n; ++j)
        A[i][j] -= f * A[k][j];
      b[i] -= f * b[k];
    }
  }
  std::vector<double> x(n);
  for (std::size_t k = n; k-- > 0;)
  {
    double s = b[k];
    for (std::size_t j = k + 1; j < n; ++j)
      s -= A[k][j] * x[j];
    x[k] = s / A[k][k];
  }
  return x;
}

struct Wave
{
  std::array<double, 2> polarisation;
  double delay;  ///< arrival at the monitor after the incident pulse [s]
  double factor; ///< energy flux per |A|^2 relative to the incident one
};

} // namespace

LysmerMeasurement measure_lysmer_reflection(const LysmerMeasurementSettings& s)
{
  const auto start = std::chrono::steady_clock::now();
  const double f0 = s.frequency;
  const double theta = s.angle_deg * M_PI / 180.0;
  const bool p_in = s.incident == IncidentKind::p;
  const double c_in = p_in ? vp : vs;
  const double p = std::sin(theta) / c_in;
  const double eta_in = std::cos(theta) / c_in; // downgoing

  LysmerMeasurement result;
  LysmerMedium medium;
  medium.density = density;
  medium.vp = vp;
  medium.vs = vs;
  result.analytic = lysmer_reflection(s.incident, theta, medium);

  // Incident: direction k = (sin, -cos), polarisation k (P) or (cos, sin) (SV).
  const std::array<double, 2> k{{std::sin(theta), -std::cos(theta)}};
  const std::array<double, 2> d_in =
      p_in ? k : std::array<double, 2>{{std::cos(theta), std::sin(theta)}};

  // Monitor height: the incident pulse (duration ~2.6 / f0) has passed before the first
  // reflection arrives.
  const double half = 1.3 / f0; // half duration of the pulse
  const double y_m = p_in ? half * vp / std::cos(theta) : 2.0 * half * vs / std::cos(theta);
  const double t_m = half; // the incident pulse centre passes the monitor

  std::vector<Wave> waves;
  const double q_p = 1.0 / (vp * vp) - p * p;
  const double q_s = 1.0 / (vs * vs) - p * p;
  if (q_p >= 0.0)
  {
    const double eta = std::sqrt(q_p);
    waves.push_back(
        {{{vp * p, vp * eta}}, y_m * (eta_in + eta), vp * vp * eta / (c_in * c_in * eta_in)});
  }
  const bool p_evanescent = q_p < 0.0;
  {
    const double eta = std::sqrt(q_s);
    waves.push_back(
        {{{-vs * eta, vs * p}}, y_m * (eta_in + eta), vs * vs * eta / (c_in * c_in * eta_in)});
  }
  double last = 0.0;
  for (const auto& w : waves)
    last = std::max(last, w.delay);
  const double t_end = t_m + last + half;
  const double t_fit = t_m + half;

  const double reach = s.domain_factor * vp * t_end;
  const double x_m = 0.0;
  FarFieldDescription d;
  d.lower = {{x_m - reach, 0.0}};
  d.upper = {{x_m + reach, y_m + reach}};
  d.element_size = vs / f0 / s.elements_per_wavelength;
  d.degree = 2;
  d.density = density;
  d.youngs_modulus = 2.0 * density * vs * vs * 1.25;
  d.poisson_ratio = 0.25;
  for (const auto part :
       {BoundaryPart::bottom, BoundaryPart::right, BoundaryPart::top, BoundaryPart::left})
    d.boundaries.push_back({part, BoundaryKind::lysmer, 1.0, 1.0});
  d.monitors = {{"monitor", {{x_m, y_m}}}};
  d.dt = 1.0 / (f0 * s.steps_per_period);

  ElasticWaveModel model(d);
  // u = d_in F(t - t_m - k.(X - M) / c_in) at t = 0.
  auto phase = [&](const double x, const double y)
  { return -t_m - (k[0] * (x - x_m) + k[1] * (y - y_m)) / c_in; };
  model.set_initial_state(
      [&](const double x, const double y)
      {
        const double f = ricker(phase(x, y), f0);
        return std::array<double, 2>{{d_in[0] * f, d_in[1] * f}};
      },
      [&](const double x, const double y)
      {
        const double f = ricker_rate(phase(x, y), f0);
        return std::array<double, 2>{{d_in[0] * f, d_in[1] * f}};
      });

  // Least squares over the window: v(t) = sum_w (a_w g(t - t_m - tau_w) + b_w Hg(...)) d_w.
  const std::size_t n = 2 * waves.size();
  std::vector<std::vector<double>> normal(n, std::vector<double>(n, 0.0));
  std::vector<double> rhs(n, 0.0);
  const auto n_steps = static_cast<std::size_t>(std::ceil(t_end / d.dt));
  std::vector<double> basis(n);
  for (std::size_t step = 0; step < n_steps; ++step)
  {
    const auto status = model.advance(d.dt);
    if (status.outcome != StepOutcome::success)
      throw std::runtime_error(status.message);
    const double t = model.time();
    if (t < t_fit)
      continue;
    const auto v = model.sample_monitor(0).velocity;
    for (int c = 0; c < 2; ++c)
    {
      for (std::size_t w = 0; w < waves.size(); ++w)
      {
        const double tau = t - t_m - waves[w].delay;
        basis[2 * w] = waves[w].polarisation[c] * ricker_rate(tau, f0);
        basis[2 * w + 1] = waves[w].polarisation[c] * ricker_rate_hilbert(tau, f0);
      }
      for (std::size_t i = 0; i < n; ++i)
      {
        rhs[i] += basis[i] * v[c];
        for (std::size_t j = 0; j < n; ++j)
          normal[i][j] += basis[i] * basis[j];
      }
    }
  }
  const auto x = solve_dense(normal, rhs);
  std::size_t w = 0;
  if (!p_evanescent)
  {
    result.r_p = std::hypot(x[0], x[1]);
    result.energy_reflected += *result.r_p * *result.r_p * waves[0].factor;
    ++w;
  }
  result.r_s = std::hypot(x[2 * w], x[2 * w + 1]);
  result.energy_reflected += *result.r_s * *result.r_s * waves[w].factor;
  result.n_dofs = model.n_dofs();
  result.n_steps = n_steps;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

} // namespace ddafem::fem
