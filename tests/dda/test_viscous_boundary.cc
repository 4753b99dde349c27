// Viscous boundaries: VB I's threshold, orientation on inclined edges, the paper's bar
// efficiencies (Bao, Hatzor & Huang 2012, section 4.1), stability and energy accounting.
#include "dda/system.h"
#include "dda/viscous_boundary.h"
#include "row_of_blocks.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace ddafem;
using namespace ddafem::dda;

namespace
{
using test_models::nu;
using test_models::rho;
using test_models::young;
constexpr double p_joint = 2.5e12;

ModelDescription bar(std::size_t n, BoundaryType type, ImpedanceKind impedance, double dt,
                     double end_time)
{
  ModelDescription m = test_models::row_of_blocks(n, p_joint);
  m.point_loads.push_back({{0, 0.5}, {1e6, 0}, TimeFunction::sine_pulse(1.0, 100.0, 1, 0), ""});
  m.monitors.push_back({"M1", {50.5, 0.5}});
  BoundaryDescription bd;
  bd.type = type;
  bd.impedance = impedance;
  bd.on_line = true;
  bd.line_point = Point(static_cast<double>(n), 0.0);
  bd.line_direction = Vector2(0.0, 1.0);
  m.boundaries.push_back(bd);
  m.time = {dt, end_time, Integrator::dda};
  // Linear about t = 0: identical histories to updated geometry at these 2e-5 strains
  // (System.SmallDisplacementMatchesUpdatedGeometryForWaves), ten times cheaper here.
  m.geometry = GeometryMode::small_displacement;
  return m;
}

std::vector<double> stress_history(const ModelDescription& m)
{
  System s(m);
  std::vector<double> h;
  const auto n = static_cast<std::size_t>(std::llround(m.time.end_time / m.time.dt));
  for (std::size_t k = 0; k < n; ++k)
  {
    EXPECT_EQ(s.advance(m.time.dt).outcome, StepOutcome::success);
    h.push_back(s.sample_monitor(0).stress[0]);
  }
  return h;
}

/// Boundary-only efficiency (docs/reference/physics.md section 6) at M1 = 50.5 m: the reflection is
/// the difference to a 300-block bar (no reflection in the window), normalised by the free end's.
class BarEfficiency
{
public:
  explicit BarEfficiency(double dt_) : dt(dt_)
  {
    reference = stress_history(bar(300, BoundaryType::free, ImpedanceKind::textbook, dt, 0.05));
    free_reflection =
        reflection(stress_history(bar(100, BoundaryType::free, ImpedanceKind::textbook, dt, 0.05)));
  }
  double eta(BoundaryType type, ImpedanceKind impedance) const
  {
    return 100.0 * (1.0 - reflection(stress_history(bar(100, type, impedance, dt, 0.05))) /
                              free_reflection);
  }

private:
  double reflection(const std::vector<double>& h) const
  {
    // Jointed-bar speed (E in series with two springs p per m^2): 4322 m/s. The reflected pulse
    // passes M1 between (149.5 - 5) / c and 149.5 / c + 10 ms (+ 2 ms for its dispersed tail).
    const double c = std::sqrt(1.0 / (1.0 / young + 1.0 / (2.0 * p_joint)) / rho);
    const double t0 = (149.5 - 5.0) / c, t1 = 149.5 / c + 0.012;
    double largest = 0.0;
    for (std::size_t k = 0; k < h.size(); ++k)
    {
      const double t = static_cast<double>(k + 1) * dt;
      if (t >= t0 && t <= t1)
        largest = std::max(largest, std::abs(h[k] - reference[k]));
    }
    return largest;
  }
  double dt;
  std::vector<double> reference;
  double free_reflection = 0.0;
};
} // namespace

TEST(ViscousBoundary, Vb1ThresholdSolvesDEqualsX)
{
  const double x0 = vb1_source_threshold();
  EXPECT_NEAR(vb1_factor(x0), x0, 1e-12);
  EXPECT_NEAR(x0, 1.68789, 1e-4);
  // Between the paper's bounds: eq. 44 (x < 1) and the source warning at x = 2.
  EXPECT_GT(x0, 1.0);
  EXPECT_LT(x0, 2.0);
}

TEST(ViscousBoundary, InclinedEdgePutsCnOnTheNormal)
{
  // An edge at 30 degrees: the boundary stiffness maps the normal to (factor) cn n and the
  // tangent to (factor) ct t, for every type.
  const double a = M_PI / 6.0;
  const Vector2 t(std::cos(a), std::sin(a));
  const Vector2 n(std::sin(a), -std::cos(a));
  BoundaryEdge e;
  e.cn = 3.0e7;
  e.ct = 1.0e7;
  const double dt = 1e-5, mass = 2650.0;
  for (BoundaryType type : {BoundaryType::vb1, BoundaryType::vb2, BoundaryType::dashpot})
  {
    const BoundaryStep s =
        boundary_step(type, e, n, mass, dt, 0.5, 1.0, Vector2::Zero(), Vector2::Zero());
    const Vector2 kn = s.k * n, kt = s.k * t;
    EXPECT_NEAR(kn.dot(t), 0.0, 1e-9 * kn.norm());
    EXPECT_NEAR(kt.dot(n), 0.0, 1e-9 * kt.norm());
    if (type == BoundaryType::vb1)
    {
      const double xn = e.cn * dt / mass, xt = e.ct * dt / mass;
      EXPECT_NEAR(kn.dot(n), e.cn / dt * (vb1_factor(xn) - xn), 1e-6 * kn.norm());
      EXPECT_NEAR(kt.dot(t), e.ct / dt * (vb1_factor(xt) - xt), 1e-6 * kt.norm());
    }
    else
    {
      EXPECT_NEAR(kn.dot(n), 2.0 * e.cn / dt, 1e-6 * kn.norm());
      EXPECT_NEAR(kt.dot(t), 2.0 * e.ct / dt, 1e-6 * kt.norm());
    }
  }
  // The consistent dashpot's force term is +C v0 (DDA's scheme), on the normal for a normal v0.
  const BoundaryStep d =
      boundary_step(BoundaryType::dashpot, e, n, mass, dt, 0.5, 1.0, 2.0 * n, Vector2::Zero());
  EXPECT_NEAR((d.f - 2.0 * e.cn * n).norm(), 0.0, 1e-9 * e.cn);
}

TEST(ViscousBoundary, InclinedBlockIsDampedNormalToItsEdge)
{
  // A free square block rotated by 30 degrees with a dashpot on one edge. Moving along the
  // edge's normal or along the edge, its centroid keeps its direction (the normal and tangential
  // dashpots do not couple), and in the first step the boundary takes c v^2 dt with c = cn or ct:
  // the ratio of the two absorbed energies is cn / ct = VP / VS.
  const double a = M_PI / 6.0;
  const Vector2 t(std::cos(a), std::sin(a)), n(std::sin(a), -std::cos(a));
  double absorbed[2] = {0.0, 0.0};
  for (int i = 0; i < 2; ++i)
  {
    const Vector2 direction = i == 0 ? n : t;
    ModelDescription m;
    m.materials.push_back({"rock", rho, young, nu});
    BlockDescription b;
    b.vertices = {Point::Zero(), t, t - n, -n}; // first edge runs along t: its outward normal is n
    b.initial_velocity = 0.1 * direction;
    m.blocks.push_back(b);
    BoundaryDescription bd;
    bd.type = BoundaryType::dashpot;
    bd.edges = {{0, 0}};
    m.boundaries.push_back(bd);
    m.time = {1e-6, 1e-3, Integrator::newmark_trapezoidal};
    System s(m);
    ASSERT_EQ(s.advance(1e-6).outcome, StepOutcome::success);
    absorbed[i] = -s.energy().work_of_boundaries;
    for (int k = 0; k < 200; ++k)
      ASSERT_EQ(s.advance(1e-6).outcome, StepOutcome::success);
    const Vector2 v = s.blocks().list[0].velocity.head<2>();
    // Up to the edge's own rotation (about 1e-6 rad here: the tangential force acts off the
    // centroid), which turns the dashpots with the block under updated geometry.
    EXPECT_NEAR(v.dot(i == 0 ? t : n), 0.0, 1e-4 * v.norm());
    EXPECT_LT(v.norm(), 0.1); // damped
  }
  const BoundaryWaveSpeeds c = textbook_wave_speeds({"rock", rho, young, nu});
  EXPECT_GT(absorbed[1], 0.0);
  EXPECT_NEAR(absorbed[0] / absorbed[1], c.p / c.s, 0.01 * c.p / c.s);
}

TEST(ViscousBoundary, BarEfficienciesMatchThePaperAtDt1e4)
{
  // Bao et al. (2012): VB I 91.1%, VB II 62.2% at dt = 1e-4 s (boundary-only efficiency);
  // tolerance 1.5 points as the issue asks. The consistent dashpot with the effective impedance
  // absorbs at least 99%.
  const BarEfficiency eta(1e-4);
  EXPECT_NEAR(eta.eta(BoundaryType::vb1, ImpedanceKind::textbook), 91.1, 1.5);
  EXPECT_NEAR(eta.eta(BoundaryType::vb2, ImpedanceKind::textbook), 62.2, 1.5);
  EXPECT_GE(eta.eta(BoundaryType::dashpot, ImpedanceKind::effective), 99.0);
  // Here the consistent dashpot beats VB I even with the textbook impedance.
  EXPECT_GT(eta.eta(BoundaryType::dashpot, ImpedanceKind::textbook),
            eta.eta(BoundaryType::vb1, ImpedanceKind::textbook));
}

TEST(ViscousBoundary, BarEfficiencyOfVb1MatchesThePaperAtDt1e5)
{
  const BarEfficiency eta(1e-5);
  EXPECT_NEAR(eta.eta(BoundaryType::vb1, ImpedanceKind::textbook), 96.2, 1.5);
}

TEST(ViscousBoundary, EnergyLeavesThroughTheDashpot)
{
  // Trapezoidal Newmark has no algorithmic damping: what the load put in is, after the pulse
  // has left, in the boundary's work, with < 1% stored or unaccounted.
  ModelDescription m = bar(100, BoundaryType::dashpot, ImpedanceKind::effective, 1e-5, 0.04);
  m.time.integrator = Integrator::newmark_trapezoidal;
  System s(m);
  for (int k = 0; k < 4000; ++k)
    ASSERT_EQ(s.advance(1e-5).outcome, StepOutcome::success);
  const EnergyBalance e = s.energy();
  EXPECT_GT(e.work_of_loads, 400.0);
  EXPECT_NEAR(-e.work_of_boundaries, e.work_of_loads, 0.01 * e.work_of_loads);
  EXPECT_LT(e.stored(), 0.01 * e.work_of_loads);
  EXPECT_LT(std::abs(e.dissipated), 0.01 * e.work_of_loads);
}

TEST(ViscousBoundary, Vb1BeyondItsThresholdFeedsEnergyAndTheRunStops)
{
  // For a 1 m x 1 m block, x = cn dt / m = VP dt: VB I is a source above
  // dt = 1.688 / 4758 = 3.55e-4 s. At 4e-4 s the energy grows until the guard stops the run;
  // at 3e-4 s it absorbs.
  for (const double dt : {3e-4, 4e-4})
  {
    ModelDescription m = bar(60, BoundaryType::vb1, ImpedanceKind::textbook, dt, 2.0);
    m.monitors.clear();
    System s(m);
    EXPECT_EQ(stability_of(s, 0, dt).is_source, dt > 3.5e-4);
    StepStatus status;
    const auto n = static_cast<std::size_t>(std::llround(2.0 / dt));
    for (std::size_t k = 0; k < n && status.outcome == StepOutcome::success; ++k)
      status = s.advance(dt);
    if (dt > 3.5e-4)
    {
      EXPECT_EQ(status.outcome, StepOutcome::energy_growth);
      EXPECT_NE(status.message.find("feeding energy"), std::string::npos);
    }
    else
    {
      EXPECT_EQ(status.outcome, StepOutcome::success) << status.message;
      EXPECT_LT(s.energy().stored(), 0.1 * s.energy().work_of_loads);
    }
  }
}
