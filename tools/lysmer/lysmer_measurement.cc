// FE measurement of Lysmer reflection coefficients (see lysmer_measurement.h, docs/lysmer.md).
#include "tools/lysmer/lysmer_measurement.h"

#include "fem/elastic_wave_model.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <complex>
#include <limits>
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
const double inv_sqrt_pi = 1.0 / std::sqrt(M_PI);

/// Ricker wavelet A (1 - 2 a t^2) exp(-a t^2), a = (pi f0)^2, and its time derivative.
double ricker(const double t, const double f0)
{
  const double a = M_PI * M_PI * f0 * f0;
  return amplitude * (1.0 - 2.0 * a * t * t) * std::exp(-a * t * t);
}

double ricker_rate(const double t, const double f0)
{
  const double a = M_PI * M_PI * f0 * f0;
  return amplitude * std::exp(-a * t * t) * (-6.0 * a * t + 4.0 * a * a * t * t * t);
}

using cd = std::complex<double>;

/// Solves the small dense system A x = b in place (Gaussian elimination, partial pivoting; b
/// becomes x); false if A is singular to working precision. Real or complex entries; rows A[i].
template <typename Matrix, typename Vector>
bool solve_in_place(Matrix& A, Vector& b)
{
  const std::size_t n = b.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    std::size_t pivot = k;
    for (std::size_t i = k + 1; i < n; ++i)
      if (std::abs(A[i][k]) > std::abs(A[pivot][k]))
        pivot = i;
    if (std::abs(A[pivot][k]) == 0.0)
      return false;
    std::swap(A[k], A[pivot]);
    std::swap(b[k], b[pivot]);
    for (std::size_t i = k + 1; i < n; ++i)
    {
      const auto f = A[i][k] / A[k][k];
      for (std::size_t j = k; j < n; ++j)
        A[i][j] -= f * A[k][j];
      b[i] -= f * b[k];
    }
  }
  for (std::size_t k = n; k-- > 0;)
  {
    for (std::size_t j = k + 1; j < n; ++j)
      b[k] -= A[k][j] * b[j];
    b[k] /= A[k][k];
  }
  return true;
}

/// Plane waves on the uniform mesh of square FE_Q(2) elements of size h (consistent mass, exact
/// integration, as ElasticWaveModel assembles them): Bloch analysis of the periodic cell, whose
/// 4 nodes (vertex, two edge midpoints, centre) carry 8 DOFs.
class Q2Dispersion
{
public:
  Q2Dispersion(const double size, const double rho, const double lambda, const double mu) : h(size)
  {
    // 1D quadratic Lagrange functions on [0, 1] (nodes 0, 1/2, 1) at 3 Gauss points.
    const std::array<double, 3> xg{{0.5 - 0.5 * std::sqrt(0.6), 0.5, 0.5 + 0.5 * std::sqrt(0.6)}};
    const std::array<double, 3> wg{{5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0}};
    auto n1 = [](const int i, const double x)
    {
      return i == 0   ? 2.0 * (x - 0.5) * (x - 1.0)
             : i == 1 ? -4.0 * x * (x - 1.0)
                      : 2.0 * x * (x - 0.5);
    };
    auto d1 = [](const int i, const double x) {
      return i == 0 ? 4.0 * x - 3.0 : i == 1 ? 4.0 - 8.0 * x : 4.0 * x - 1.0;
    };
    // Element matrices, node a = i + 3 j at (i h / 2, j h / 2), DOF 2 a + component.
    for (int qx = 0; qx < 3; ++qx)
      for (int qy = 0; qy < 3; ++qy)
      {
        const double w = wg[qx] * wg[qy] * h * h;
        std::array<double, 9> n{};
        std::array<std::array<double, 2>, 9> g{};
        for (int a = 0; a < 9; ++a)
        {
          const int i = a % 3, j = a / 3;
          n[a] = n1(i, xg[qx]) * n1(j, xg[qy]);
          g[a] = {{d1(i, xg[qx]) * n1(j, xg[qy]) / h, n1(i, xg[qx]) * d1(j, xg[qy]) / h}};
        }
        for (int a = 0; a < 9; ++a)
          for (int b = 0; b < 9; ++b)
            for (int al = 0; al < 2; ++al)
              for (int be = 0; be < 2; ++be)
              {
                double k = lambda * g[a][al] * g[b][be] + mu * g[a][be] * g[b][al];
                if (al == be)
                  k += mu * (g[a][0] * g[b][0] + g[a][1] * g[b][1]);
                ke[2 * a + al][2 * b + be] += w * k;
                if (al == be)
                  me[2 * a + al][2 * b + be] += w * rho * n[a] * n[b];
              }
      }
  }

  /// Angular frequency of the acoustic P (or S) mode of wavevector (kx, ky); nullopt if the
  /// Rayleigh quotient iteration from the continuum mode does not settle.
  std::optional<double> frequency(const double kx, const double ky, const bool p_mode) const
  {
    // Bloch matrices: nodal values phi_c exp(i k.(cell offset)).
    std::array<std::array<cd, 8>, 8> K{}, M{};
    for (int a = 0; a < 9; ++a)
      for (int b = 0; b < 9; ++b)
      {
        const cd phase = std::polar(
            1.0, h * (kx * (offset(a % 3) - offset(b % 3)) + ky * (offset(a / 3) - offset(b / 3))));
        for (int al = 0; al < 2; ++al)
          for (int be = 0; be < 2; ++be)
          {
            // conj(e^{ik.o_a}) K_ab e^{ik.o_b}
            const cd f = std::conj(phase);
            K[2 * cls(a) + al][2 * cls(b) + be] += f * ke[2 * a + al][2 * b + be];
            M[2 * cls(a) + al][2 * cls(b) + be] += f * me[2 * a + al][2 * b + be];
          }
      }
    // Start: the continuum mode d exp(i k.x) at the cell's nodes.
    const double k = std::hypot(kx, ky);
    if (k == 0.0)
      return 0.0;
    const std::array<double, 2> d =
        p_mode ? std::array<double, 2>{{kx / k, ky / k}} : std::array<double, 2>{{-ky / k, kx / k}};
    std::array<cd, 8> x{};
    for (int c = 0; c < 4; ++c)
    {
      const cd e = std::polar(1.0, 0.5 * h * (kx * (c % 2) + ky * (c / 2)));
      x[2 * c] = d[0] * e;
      x[2 * c + 1] = d[1] * e;
    }
    auto quotient = [&](const std::array<cd, 8>& y)
    {
      cd num = 0.0, den = 0.0;
      for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j)
        {
          num += std::conj(y[i]) * K[i][j] * y[j];
          den += std::conj(y[i]) * M[i][j] * y[j];
        }
      return num.real() / den.real();
    };
    double sigma = quotient(x);
    for (int it = 0; it < 8; ++it)
    {
      auto A = K;
      std::array<cd, 8> y{};
      for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j)
        {
          A[i][j] -= sigma * M[i][j];
          y[i] += M[i][j] * x[j];
        }
      if (!solve_in_place(A, y))
        break;
      double norm = 0.0;
      for (const auto& v : y)
        norm += std::norm(v);
      norm = std::sqrt(norm);
      if (!(norm > 0.0) || !std::isfinite(norm))
        break;
      for (int i = 0; i < 8; ++i)
        x[i] = y[i] / norm;
      const double next = quotient(x);
      const bool done = std::abs(next - sigma) <= 1e-13 * std::abs(next);
      sigma = next;
      if (done)
        return std::sqrt(sigma);
    }
    return std::nullopt;
  }

  /// The vertical wavenumber ky >= 0 of the P (or S) mode with horizontal wavenumber kx and
  /// angular frequency omega (secant iteration from the continuum value c_guess); nullopt if
  /// evanescent or not found.
  std::optional<double> vertical_wavenumber(const double kx, const double omega, const double c,
                                            const bool p_mode) const
  {
    const double q = omega * omega / (c * c) - kx * kx;
    if (q <= 0.0)
      return std::nullopt;
    double k0 = std::sqrt(q), k1 = k0 * (1.0 + 1e-3) + 1e-9;
    auto f = [&](const double ky) -> std::optional<double>
    {
      const auto w = frequency(kx, ky, p_mode);
      if (!w)
        return std::nullopt;
      return *w - omega;
    };
    auto f0 = f(k0), f1 = f(k1);
    for (int it = 0; it < 30 && f0 && f1; ++it)
    {
      if (std::abs(*f1) <= 1e-12 * omega)
        return k1;
      if (*f1 == *f0)
        break;
      const double k2 = k1 - *f1 * (k1 - k0) / (*f1 - *f0);
      k0 = k1;
      f0 = f1;
      k1 = k2;
      f1 = f(k1);
    }
    return std::nullopt;
  }

private:
  static int offset(const int i) { return i == 2 ? 1 : 0; } ///< cell offset of local index i
  static int cls(const int a) { return (a % 3) % 2 + 2 * ((a / 3) % 2); } ///< node class 0..3
  double h;
  std::array<std::array<double, 18>, 18> ke{}, me{};
};

/// A pulse at the monitor as a sum over angular frequencies W_j of the continuum (the spatial
/// frequencies of the initial data): g_a(t) = sum_j c_j exp(i (w_j t - phi_j)), g + i H[g].
/// For the incident pulse with no discretization, w_j = W_j and phi_j = W_j T reproduce
/// g(t - T) + i H[g](t - T), g the Ricker velocity pulse.
struct MonitorPulse
{
  std::vector<cd> coefficient;
  std::vector<double> omega;
  std::vector<double> phase;
  cd operator()(const double t) const
  {
    cd sum = 0.0;
    for (std::size_t j = 0; j < omega.size(); ++j)
      sum += coefficient[j] * std::polar(1.0, omega[j] * t - phase[j]);
    return sum;
  }
};

/// Frequency samples: Simpson weights times (1/pi) G(W), G(W) = i W R(W) the Fourier transform
/// of the Ricker velocity pulse, R(W) = A W^2/(2a) sqrt(pi/a) exp(-W^2/(4a)), a = (pi f0)^2.
/// The phase step W_max t / intervals stays << 1 for t < 2 s.
MonitorPulse ricker_samples(const double f0)
{
  const double a = M_PI * M_PI * f0 * f0;
  const double w_max = 10.0 * M_PI * f0; // exp(-W^2/(4a)) = exp(-25)
  const int intervals = 4000;
  const double h = w_max / intervals;
  MonitorPulse pulse;
  for (int j = 1; j <= intervals; ++j) // the integrand vanishes at W = 0
  {
    const double w = j * h;
    const double spectrum =
        amplitude * w * w * w / (2.0 * a) * std::sqrt(M_PI / a) * std::exp(-w * w / (4.0 * a));
    const double weight = j == intervals ? 1.0 : (j % 2 == 1 ? 4.0 : 2.0);
    pulse.coefficient.push_back(cd(0.0, weight * spectrum * h / (3.0 * M_PI)));
    pulse.omega.push_back(w);
    pulse.phase.push_back(0.0);
  }
  return pulse;
}

/// x with A x = b (NaN where A is singular: the fit has no solution).
std::vector<double> solve_dense(std::vector<std::vector<double>> A, std::vector<double> b)
{
  if (!solve_in_place(A, b))
    b.assign(b.size(), std::numeric_limits<double>::quiet_NaN());
  return b;
}

/// A reflected (upgoing, propagating) plane wave: displacement d (a F(tau) + b H[F](tau)) with
/// tau = t - t_m - p (x - x_m) - eta_in y_m - eta y (phase-matched with the incident on y = 0).
struct Wave
{
  std::array<double, 2> polarisation; ///< unit
  double eta;                         ///< vertical slowness [s/m]
  double tan_angle;                   ///< tan of the angle from the boundary normal
  double delay = 0.0;                 ///< arrival at the monitor after the incident pulse [s]
  double factor = 0.0;                ///< energy flux per |A|^2 relative to the incident one
  double a = 0.0;                     ///< in-phase coefficient
  double b = 0.0;                     ///< quadrature coefficient
};

} // namespace

double dawson(const double x)
{
  // Rybicki's method (Numerical Recipes 6.10) with step h = 0.2: the error ~exp(-(pi/2h)^2) is
  // below double precision.
  constexpr double h = 0.2;
  const double ax = std::abs(x);
  const int n0 = 2 * static_cast<int>(std::lround(0.5 * ax / h));
  const double xp = ax - n0 * h;
  double sum = 0.0;
  for (int n = 1; n <= 41; n += 2)
  {
    sum += std::exp(-(xp - n * h) * (xp - n * h)) / (n0 + n);
    sum += std::exp(-(xp + n * h) * (xp + n * h)) / (n0 - n);
  }
  return std::copysign(sum * inv_sqrt_pi, x);
}

// H[exp(-a t^2)] = (2/sqrt(pi)) D(sqrt(a) t) (D Dawson's function); the Ricker wavelet is
// -A/(2a) d^2/dt^2 exp(-a t^2), and H commutes with d/dt. With x = sqrt(a) t:
// D' = 1 - 2xD, D'' = (4x^2 - 2) D - 2x, D''' = (12x - 8x^3) D + 4x^2 - 4.
double ricker_hilbert(const double t, const double f0)
{
  const double x = M_PI * f0 * t;
  const double d = dawson(x);
  return -amplitude * inv_sqrt_pi * ((4.0 * x * x - 2.0) * d - 2.0 * x);
}

double ricker_rate_hilbert(const double t, const double f0)
{
  const double x = M_PI * f0 * t;
  const double d = dawson(x);
  return -amplitude * inv_sqrt_pi * M_PI * f0 *
         ((12.0 * x - 8.0 * x * x * x) * d + 4.0 * x * x - 4.0);
}

namespace
{
/// The experiment: the incident wave, the reflected waves it meets at the monitor and the time
/// window of each run (docs/lysmer.md, FE measurement).
struct Experiment
{
  double f0 = 0.0;              ///< Ricker peak frequency [Hz]
  bool p_in = true;             ///< incident P (else SV)
  double c_in = 0.0;            ///< incident wave speed [m/s]
  double p = 0.0;               ///< horizontal slowness [s/m]
  double eta_in = 0.0;          ///< vertical slowness of the (downgoing) incident wave [s/m]
  std::array<double, 2> d_in{}; ///< incident polarisation
  std::vector<Wave> waves;      ///< reflected propagating waves: P (unless evanescent), then S
  bool p_evanescent = false;
  double half = 0.0;           ///< half the duration of the pulse [s]
  double x_m = 0.0, y_m = 0.0; ///< the monitor [m]
  double t_m = 0.0;            ///< the incident pulse centre passes the monitor [s]
  double t_fit = 0.0;          ///< start of the fitted window [s]
  double t_end = 0.0;          ///< end of each run [s]
};

/// The incident wave and the reflected propagating waves with their flux factors.
Experiment plan_waves(const LysmerMeasurementSettings& s)
{
  Experiment e;
  e.f0 = s.frequency;
  const double theta = s.angle_deg * M_PI / 180.0;
  e.p_in = s.incident == IncidentKind::p;
  e.c_in = e.p_in ? vp : vs;
  e.p = std::sin(theta) / e.c_in;
  e.eta_in = std::cos(theta) / e.c_in; // downgoing
  const double p = e.p, c_in = e.c_in, eta_in = e.eta_in;

  // Incident: direction k = (sin, -cos), polarisation k (P) or (cos, sin) (SV).
  const std::array<double, 2> k{{std::sin(theta), -std::cos(theta)}};
  e.d_in = e.p_in ? k : std::array<double, 2>{{std::cos(theta), std::sin(theta)}};

  // Reflected propagating waves: P (unless evanescent), then S.
  const double q_p = 1.0 / (vp * vp) - p * p;
  e.p_evanescent = q_p < 0.0;
  if (!e.p_evanescent)
  {
    const double eta = std::sqrt(q_p);
    e.waves.push_back(
        {{{vp * p, vp * eta}}, eta, p / eta, 0.0, vp * vp * eta / (c_in * c_in * eta_in)});
  }
  {
    const double eta = std::sqrt(1.0 / (vs * vs) - p * p);
    e.waves.push_back(
        {{{-vs * eta, vs * p}}, eta, p / eta, 0.0, vs * vs * eta / (c_in * c_in * eta_in)});
  }
  return e;
}

/// The monitor height, the delays of the reflected waves and the window of each run.
void plan_window(const LysmerMeasurementSettings& s, Experiment& e)
{
  // Monitor height: the incident pulse (duration 2 half) has passed before the first
  // reflection arrives.
  const double f0 = e.f0;
  e.half = 1.3 / f0;
  const double half = e.half;
  double eta_min = e.waves.front().eta;
  for (const auto& w : e.waves)
    eta_min = std::min(eta_min, w.eta);
  e.y_m = 2.0 * half / (e.eta_in + eta_min);
  e.x_m = 0.0;
  // The incident pulse centre passes the monitor at t_m. The specular point of wave w,
  // x_m - y_m tan(angle_w), is reached by the pulse centre at t_m + y_m (eta_in - p tan_w);
  // the pulse front must get there no earlier than margin after t = 0.
  const double margin = s.margin_periods / f0;
  e.t_m = half;
  for (const auto& w : e.waves)
    e.t_m = std::max(e.t_m, half + margin - e.y_m * (e.eta_in - e.p * w.tan_angle));
  double last = 0.0;
  for (auto& w : e.waves)
  {
    w.delay = e.y_m * (e.eta_in + w.eta);
    last = std::max(last, w.delay);
  }
  e.t_end = e.t_m + last + half;
  e.t_fit = e.t_m + half;
}

/// Whether nothing a side from a to b does reaches the monitor before t_goal: a side point B
/// disturbs the field once a plane wave (incident, reflected P or S, as if the whole plane wave
/// existed) is there, no earlier than t_c(B) - half (t_c: arrival of the pulse centre) and not
/// before t = 0 (where the initial stripes are cut by the side), if the pulse has not passed B
/// before t = 0 (t_c(B) >= -half); the disturbance travels at most at VP. h: element size [m].
bool side_clear(const Experiment& e, const double h, const std::array<double, 2>& a,
                const std::array<double, 2>& b)
{
  const double t0_front = e.t_m + e.eta_in * e.y_m;
  std::vector<double> front_eta{-e.eta_in};
  for (const auto& w : e.waves)
    front_eta.push_back(w.eta);
  const double t_goal = e.t_end + 0.25 / e.f0;
  const double length = std::hypot(b[0] - a[0], b[1] - a[1]);
  const int n_points = 1 + static_cast<int>(std::ceil(2.0 * length / h));
  for (int i = 0; i <= n_points; ++i)
  {
    const double x = a[0] + (b[0] - a[0]) * i / n_points;
    const double y = a[1] + (b[1] - a[1]) * i / n_points;
    const double travel = std::hypot(x - e.x_m, y - e.y_m) / vp;
    for (const double ey : front_eta)
    {
      const double t_c = t0_front + e.p * (x - e.x_m) + ey * y;
      if (t_c >= -e.half && std::max(t_c - e.half, 0.0) + travel < t_goal)
        return false;
    }
  }
  return true;
}

/// Distances (left, right, top) [m] of the sides of the domain [x_m - left, x_m + right] x
/// [0, top] from the monitor: nothing the sides do may reach the monitor before t_end
/// (side_clear); each side is moved in as far as this allows (bisection).
std::array<double, 3> clear_extent(const Experiment& e, const double h)
{
  const double t_goal = e.t_end + 0.25 / e.f0;
  std::array<double, 3> extent{{vp * t_goal, vp * t_goal, e.y_m + vp * t_goal}};
  auto clear = [&](const std::array<double, 3>& x)
  {
    const double xl = e.x_m - x[0], xr = e.x_m + x[1], yt = x[2];
    return side_clear(e, h, {{xl, 0.0}}, {{xl, yt}}) && side_clear(e, h, {{xr, 0.0}}, {{xr, yt}}) &&
           side_clear(e, h, {{xl, yt}}, {{xr, yt}});
  };
  for (int sweep = 0; sweep < 2; ++sweep)
    for (int side = 0; side < 3; ++side)
    {
      double lo = side == 2 ? e.y_m + 2.0 * h : 2.0 * h, hi = extent[side];
      for (int it = 0; it < 30 && hi - lo > 0.25 * h; ++it)
      {
        auto x = extent;
        x[side] = 0.5 * (lo + hi);
        (clear(x) ? hi : lo) = x[side];
      }
      extent[side] = hi;
    }
  return extent;
}

/// The far field: the clear extent scaled by domain_factor, square Q2 elements of size h (the
/// sides multiples of h, the monitor column on vertices), Lysmer dashpots on every side.
FarFieldDescription experiment_far_field(const LysmerMeasurementSettings& s, const Experiment& e,
                                         const double h)
{
  const std::array<double, 3> extent = clear_extent(e, h);
  auto multiple = [&](const double length) { return h * std::ceil(length / h - 1e-9); };
  FarFieldDescription d;
  d.lower = {{e.x_m - multiple(s.domain_factor * extent[0]), 0.0}};
  d.upper = {{e.x_m + multiple(s.domain_factor * extent[1]),
              multiple(e.y_m + s.domain_factor * (extent[2] - e.y_m))}};
  d.element_size = h;
  d.degree = 2;
  d.density = density;
  d.youngs_modulus = 2.0 * density * vs * vs * 1.25;
  d.poisson_ratio = 0.25;
  for (const auto part :
       {BoundaryPart::bottom, BoundaryPart::right, BoundaryPart::top, BoundaryPart::left})
    d.boundaries.push_back({part, BoundaryKind::lysmer, 1.0, 1.0, {}});
  d.monitors = {{"monitor", {{e.x_m, e.y_m}}}};
  d.dt = 1.0 / (e.f0 * s.steps_per_period);
  return d;
}

/// Displacement (or, with `rate`, velocity) at (x, y) at time 0 of a run: the incident wave
/// plus the reflected waves of the previous run.
std::array<double, 2> initial_field(const Experiment& e, const double x, const double y,
                                    const bool rate)
{
  const double f0 = e.f0;
  const double tau = -e.t_m - e.p * (x - e.x_m) + e.eta_in * (y - e.y_m);
  const double f = rate ? ricker_rate(tau, f0) : ricker(tau, f0);
  std::array<double, 2> u{{e.d_in[0] * f, e.d_in[1] * f}};
  for (const auto& w : e.waves)
  {
    if (w.a == 0.0 && w.b == 0.0)
      continue;
    const double t = -e.t_m - e.p * (x - e.x_m) - e.eta_in * e.y_m - w.eta * y;
    const double g = rate ? w.a * ricker_rate(t, f0) + w.b * ricker_rate_hilbert(t, f0)
                          : w.a * ricker(t, f0) + w.b * ricker_hilbert(t, f0);
    u[0] += w.polarisation[0] * g;
    u[1] += w.polarisation[1] * g;
  }
  return u;
}

/// The incident and reflected pulses at the monitor.
struct MonitorPulses
{
  MonitorPulse incident;
  std::vector<MonitorPulse> reflected; ///< one per wave of Experiment::waves
};

/// The pulses with the dispersion of the mesh and of the trapezoidal rule if asked
/// (docs/lysmer.md); h: element size [m], dt: time step [s].
MonitorPulses monitor_pulses(const LysmerMeasurementSettings& s, const Experiment& e,
                             const double h, const double dt)
{
  const double mu = density * vs * vs;
  const Q2Dispersion mesh(h, density, density * vp * vp - 2.0 * mu, mu);
  MonitorPulses pulses;
  pulses.incident = ricker_samples(e.f0);
  pulses.reflected.assign(e.waves.size(), pulses.incident);
  for (std::size_t j = 0; j < pulses.incident.omega.size(); ++j)
  {
    const double W = pulses.incident.omega[j];
    const double kx = W * e.p, ky = -W * e.eta_in;
    double w_h = W;
    if (s.mesh_dispersion)
      w_h = mesh.frequency(kx, ky, e.p_in).value_or(W);
    const double w_t = s.warp_time ? 2.0 / dt * std::atan(0.5 * w_h * dt) : w_h;
    pulses.incident.omega[j] = w_t;
    pulses.incident.phase[j] = W * e.t_m;
    for (std::size_t i = 0; i < e.waves.size(); ++i)
    {
      const bool p_mode = !e.p_evanescent && i == 0;
      double k_w = W * e.waves[i].eta;
      if (s.mesh_dispersion)
        k_w = mesh.vertical_wavenumber(kx, w_h, p_mode ? vp : vs, p_mode).value_or(k_w);
      pulses.reflected[i].omega[j] = w_t;
      pulses.reflected[i].phase[j] = W * (e.t_m + e.eta_in * e.y_m) + k_w * e.y_m;
    }
  }
  return pulses;
}

/// Least squares of one run: over the window, v(t) = sum_w (a_w g(t - t_m - tau_w) +
/// b_w Hg(...)) d_w; before it, the incident pulse along d_in (a check of the discrete
/// propagation).
struct RunFit
{
  explicit RunFit(const std::size_t n) : normal(n, std::vector<double>(n, 0.0)), rhs(n, 0.0) {}
  std::vector<std::vector<double>> normal; ///< normal equations of the reflected waves
  std::vector<double> rhs;
  double vv = 0.0;          ///< |v|^2 over the window
  double incident_vv = 0.0; ///< |incident pulse|^2 over the run
  std::array<std::array<double, 2>, 2> in_n{};
  std::array<double, 2> in_r{};
  std::vector<std::array<double, 3>> record; ///< (t, v_x, v_y) with record_trace

  /// Adds the monitor velocity v at time t of the run.
  void add(const Experiment& e, const MonitorPulses& pulses, const double t,
           const std::array<double, 2>& v)
  {
    const double g_in = ricker_rate(t - e.t_m, e.f0);
    incident_vv += g_in * g_in;
    if (t < e.t_fit)
    {
      const auto pulse = pulses.incident(t);
      const double vd = v[0] * e.d_in[0] + v[1] * e.d_in[1];
      in_n[0][0] += pulse.real() * pulse.real();
      in_n[0][1] += pulse.real() * pulse.imag();
      in_n[1][1] += pulse.imag() * pulse.imag();
      in_r[0] += pulse.real() * vd;
      in_r[1] += pulse.imag() * vd;
      return;
    }
    std::vector<std::complex<double>> g(e.waves.size());
    for (std::size_t w = 0; w < e.waves.size(); ++w)
      g[w] = pulses.reflected[w](t);
    std::vector<double> basis(rhs.size());
    for (int c = 0; c < 2; ++c)
    {
      for (std::size_t w = 0; w < e.waves.size(); ++w)
      {
        basis[2 * w] = e.waves[w].polarisation[c] * g[w].real();
        basis[2 * w + 1] = e.waves[w].polarisation[c] * g[w].imag();
      }
      for (std::size_t i = 0; i < rhs.size(); ++i)
      {
        rhs[i] += basis[i] * v[c];
        for (std::size_t j = 0; j < rhs.size(); ++j)
          normal[i][j] += basis[i] * basis[j];
      }
      vv += v[c] * v[c];
    }
  }
};

/// Advances the model over one run (n_steps of dt [s]) from the experiment's initial state.
RunFit record_run(const LysmerMeasurementSettings& s, const Experiment& e,
                  const MonitorPulses& pulses, const std::size_t n_steps, const double dt,
                  ElasticWaveModel& model)
{
  const double t0 = model.time();
  model.set_initial_state(
      [&](const double x, const double y) { return initial_field(e, x, y, false); },
      [&](const double x, const double y) { return initial_field(e, x, y, true); });
  RunFit fit(2 * e.waves.size());
  for (std::size_t step = 0; step < n_steps; ++step)
  {
    const auto status = model.advance(dt);
    if (!status.taken)
      throw std::runtime_error(status.why);
    const double t = model.time() - t0;
    const auto v = model.sample_monitor(0).velocity;
    if (s.record_trace)
      fit.record.push_back({{t, v[0], v[1]}});
    fit.add(e, pulses, t, v);
  }
  return fit;
}

/// Solves the run's fit, stores the coefficients in the experiment's waves for the next run;
/// `change`: the largest change of a coefficient.
LysmerRun evaluate_run(RunFit& fit, const MonitorPulses& pulses, Experiment& e, double& change)
{
  const std::size_t n = fit.rhs.size();
  const auto x = solve_dense(fit.normal, fit.rhs);
  // Residual: |v - B x|^2 = v.v - 2 x.rhs + x.N x.
  double res = fit.vv;
  for (std::size_t i = 0; i < n; ++i)
  {
    res -= 2.0 * x[i] * fit.rhs[i];
    for (std::size_t j = 0; j < n; ++j)
      res += x[i] * fit.normal[i][j] * x[j];
  }
  LysmerRun r;
  auto& in_n = fit.in_n;
  in_n[1][0] = in_n[0][1];
  const auto in_x =
      solve_dense({{in_n[0][0], in_n[0][1]}, {in_n[1][0], in_n[1][1]}}, {fit.in_r[0], fit.in_r[1]});
  r.incident = std::hypot(in_x[0], in_x[1]);
  r.rms_residual = std::sqrt(std::max(res, 0.0) / fit.incident_vv);
  change = 0.0;
  std::vector<Wave>& waves = e.waves;
  for (std::size_t w = 0; w < waves.size(); ++w)
  {
    change =
        std::max({change, std::abs(x[2 * w] - waves[w].a), std::abs(x[2 * w + 1] - waves[w].b)});
    waves[w].a = x[2 * w];
    waves[w].b = x[2 * w + 1];
    r.coefficients.push_back({{x[2 * w], x[2 * w + 1]}});
  }
  const std::size_t s_wave = e.p_evanescent ? 0 : 1;
  if (!e.p_evanescent)
    r.r_p = std::hypot(waves[0].a, waves[0].b);
  r.r_s = std::hypot(waves[s_wave].a, waves[s_wave].b);
  for (const auto& [t, vx, vy] : fit.record)
  {
    std::array<double, 2> v_fit{{0.0, 0.0}};
    for (std::size_t j = 0; j < waves.size(); ++j)
    {
      const auto pulse = pulses.reflected[j](t);
      const double g = x[2 * j] * pulse.real() + x[2 * j + 1] * pulse.imag();
      v_fit[0] += waves[j].polarisation[0] * g;
      v_fit[1] += waves[j].polarisation[1] * g;
    }
    r.trace.push_back({{t, vx, vy, v_fit[0], v_fit[1]}});
  }
  return r;
}
} // namespace

LysmerMeasurement measure_lysmer_reflection(const LysmerMeasurementSettings& s)
{
  const auto start = std::chrono::steady_clock::now();
  LysmerMeasurement result;
  LysmerMedium medium;
  medium.density = density;
  medium.vp = vp;
  medium.vs = vs;
  result.analytic = lysmer_reflection(s.incident, s.angle_deg * M_PI / 180.0, medium);

  Experiment e = plan_waves(s);
  plan_window(s, e);
  const double h = vs / e.f0 / s.elements_per_wavelength;
  const FarFieldDescription d = experiment_far_field(s, e, h);
  ElasticWaveModel model(d);
  const auto n_steps = static_cast<std::size_t>(std::ceil(e.t_end / d.dt));
  const MonitorPulses pulses = monitor_pulses(s, e, h, d.dt);

  const unsigned int max_runs = std::max(1u, s.max_runs);
  for (unsigned int run = 0; run < max_runs; ++run)
  {
    RunFit fit = record_run(s, e, pulses, n_steps, d.dt, model);
    double change = 0.0;
    result.runs.push_back(evaluate_run(fit, pulses, e, change));
    if (change < s.tolerance)
      break;
  }
  result.r_p = result.runs.back().r_p;
  result.r_s = result.runs.back().r_s;
  for (const auto& w : e.waves)
    result.energy_reflected += (w.a * w.a + w.b * w.b) * w.factor;
  result.domain = {{d.lower[0], d.upper[0], d.upper[1]}};
  result.monitor_height = e.y_m;
  result.window = {{e.t_fit, e.t_end}};
  result.n_dofs = model.n_dofs();
  result.n_steps = n_steps;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

} // namespace ddafem::fem
