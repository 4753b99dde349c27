// The frictional tie interface between DDA blocks and the deal.II far field (issue 6): one
// block resting under gravity on a far-field slab, tied by Mohr-Coulomb ties (zero cohesion and
// tensile strength), against hand calculations of a rigid block on a rough floor: it sticks
// below the friction limit, slides at a = (F - mu m g) / m above it and stops at a = -mu g
// after the load is removed; a pull larger than its weight lifts it off at a = (F - m g) / m.
// A bonded interface (infinite strength) never slides nor opens.
//
// The model, per metre of thickness: a block [0, 2] x [0, 1] m (rho 2650 kg/m^3, E 50 GPa,
// nu 0.25, plane strain, trapezoidal rule, updated geometry) on a far field [0, 2] x [-1, 0] m
// of the same rock (degree 2, 0.5 m elements, fixed bottom, free sides, top = the interface, no
// gravity), m g = 2650 x 2 x 9.81 = 51993 N. The block is released at t = 0 onto the unloaded
// slab: it bounces on it at about 600 Hz (the slab's and the ties' 8e10 N/m against its
// 5300 kg). Nothing in the model is dissipative but the ties, so the far field carries
// stiffness-proportional Rayleigh damping (beta = 3e-4 s: damping ratio beta omega / 2 ~ 0.6 at
// 600 Hz) to settle the block before the loads start at t = 30 ms (the ties then carry m g to
// 1e-6, the prints). It does nothing once the far field is at rest: a sliding
// block drags a far field in steady shear.
#include "coupling/far_field_ties.h"
#include "dda/model_description.h"
#include "dda/system.h"
#include "fem/elastic_wave_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>
#include <vector>

namespace ddafem::coupling
{
namespace
{
constexpr double rho = 2650.0, young = 50e9, poisson = 0.25; // [kg/m^3], [Pa], [-]
constexpr double gravity = 9.81;                             // [m/s^2]
constexpr double width = 2.0, height = 1.0, depth = 1.0;     // block, block, slab [m]
constexpr double mass = rho * width * height;                // [kg/m]
constexpr double weight = mass * gravity;                    // m g [N/m]
constexpr double dt = 1e-4;                                  // [s]
constexpr double settled = 0.03;                             // loads start [s]
/// Tie normal spring p [N/m] at each end of the block's base (10 E: stiff against the slab's
/// 4e10 to 1e11 N/m, so that the ties' elastic stretch is small against the slab's).
constexpr double tie_stiffness = 10.0 * young;

const double tan_phi = std::tan(30.0 * M_PI / 180.0); // mu for the 30 deg friction angle

dda::ModelDescription block_model(const std::vector<dda::PointLoad>& loads)
{
  dda::ModelDescription m;
  m.plane_mode = dda::PlaneMode::strain;
  m.geometry = dda::GeometryMode::updated;
  m.materials.push_back({"rock", rho, young, poisson});
  dda::BlockDescription b;
  b.vertices = {{0.0, 0.0}, {width, 0.0}, {width, height}, {0.0, height}};
  m.blocks.push_back(b);
  m.point_loads = loads;
  // The centroid: its displacement and velocity are the block's translation (the strain and
  // rotation terms of T vanish there).
  m.monitors.push_back({"centroid", {0.5 * width, 0.5 * height}});
  m.gravity = {0.0, -gravity};
  m.time.dt = dt;
  m.time.end_time = 1.0;
  m.time.integrator = dda::Integrator::newmark_trapezoidal;
  m.time.control = dda::TimeControl::fixed;
  return m;
}

fem::FarFieldDescription slab()
{
  fem::FarFieldDescription d;
  d.lower = {{0.0, -depth}};
  d.upper = {{width, 0.0}};
  d.element_size = 0.5;
  d.degree = 2;
  d.density = rho;
  d.youngs_modulus = young;
  d.poisson_ratio = poisson;
  d.plane_mode = fem::PlaneMode::strain;
  fem::BoundaryCondition bottom;
  bottom.part = fem::BoundaryPart::bottom;
  bottom.kind = fem::BoundaryKind::fixed;
  d.boundaries.push_back(bottom);
  d.dt = dt;
  d.integrator = fem::Integrator::newmark_trapezoidal;
  d.rayleigh.beta = 3e-4;
  return d;
}

/// Ties on the slab's top; finite strength: Mohr-Coulomb with phi = 30 deg, no cohesion, no
/// tensile strength.
InterfaceDescription interface(bool frictional)
{
  InterfaceDescription i;
  i.part = fem::BoundaryPart::top;
  i.normal_stiffness = tie_stiffness;
  if (frictional)
  {
    i.cohesion = 0.0;
    i.tensile_strength = 0.0;
    i.friction_angle = 30.0;
  }
  return i;
}

/// A load `force` [N] at `point` [m] scaled by the piecewise-linear f(t) of (times, values).
dda::PointLoad load(const dda::Point& point, const dda::Vector2& force, std::vector<double> times,
                    std::vector<double> values)
{
  dda::PointLoad l;
  l.point = point;
  l.force = force;
  l.time_function = TimeFunction::table(std::move(times), std::move(values));
  return l;
}

/// A horizontal load at the middle of the base: it and the friction act on the same line, so
/// that the block slides without tipping. The inertia force m a at the centroid, 0.5 m above,
/// still shifts the base pressure towards the trailing edge: at a = mu g / 2 every tie stays
/// closed, at a = mu g the leading one opens.
dda::PointLoad horizontal(double force, std::vector<double> times, std::vector<double> values)
{
  return load({0.5 * width, 0.0}, {force, 0.0}, std::move(times), std::move(values));
}

struct BlockOnSlab
{
  BlockOnSlab(const InterfaceDescription& tie, const std::vector<dda::PointLoad>& loads)
      : system(block_model(loads)), far_field(std::make_unique<fem::ElasticWaveModel>(slab())),
        ties(std::make_unique<FarFieldTies>(system, *far_field, tie))
  {
  }

  /// Steps to time t [s]; false (with a test failure) if a step fails.
  bool run_until(double t)
  {
    while (system.time() < t - 0.5 * dt)
    {
      const dda::StepStatus status = system.advance(dt);
      if (status.outcome != dda::StepOutcome::success)
      {
        ADD_FAILURE() << status.message;
        return false;
      }
    }
    return true;
  }

  dda::Vector2 displacement() const { return system.sample_monitor(0).displacement; }
  dda::Vector2 velocity() const { return system.sample_monitor(0).velocity; }

  /// Sum of the ties' normal forces (compression positive) and shear forces (S t on the far
  /// field) [N].
  std::pair<double, double> tie_forces() const
  {
    double n = 0.0, s = 0.0;
    for (const Tie& t : ties->get_ties())
    {
      n += t.forces.normal_force;
      s += t.forces.shear_force;
    }
    return {n, s};
  }

  /// Energy the tie springs hold [J]: N^2 / (2 p) + S^2 / (2 p_s) of each closed tie.
  double elastic_tie_energy() const
  {
    double e = 0.0;
    for (const Tie& t : ties->get_ties())
      if (t.forces.state != dda::ContactState::open)
        e += 0.5 * t.forces.normal_force * t.forces.normal_force / t.law.normal_stiffness +
             0.5 * t.forces.shear_force * t.forces.shear_force / t.law.shear_stiffness;
    return e;
  }

  /// Energy the ties dissipated by friction (and lost on opening) [J]: what crossed into them
  /// less what they hold.
  double friction_dissipation() const { return ties->tie_energy() - elastic_tie_energy(); }

  void print(const char* label) const
  {
    const TieCounts c = ties->counts();
    const auto [n, s] = tie_forces();
    const dda::EnergyBalance e = system.energy();
    std::printf("%s t = %.4f s: u = (%.4e, %.4e) m, v = (%.4e, %.4e) m/s, N / mg = %.6f, "
                "S / mg = %.6f, ties intact/lock/slide/open %zu/%zu/%zu/%zu, work on blocks "
                "%.6g J, on far field %.6g J, tie energy %.6g J (friction %.6g J)\n",
                label, system.time(), displacement().x(), displacement().y(), velocity().x(),
                velocity().y(), n / weight, s / weight, c.intact, c.lock, c.slide, c.open,
                e.work_of_ties, ties->work_on_far_field(), ties->tie_energy(),
                friction_dissipation());
  }

  dda::System system;
  std::unique_ptr<fem::ElasticWaveModel> far_field;
  std::unique_ptr<FarFieldTies> ties;
};

/// The block settles on the slab: the ties carry its weight, in compression, none slides.
TEST(FrictionalInterface, BlockSettlesUnderGravity)
{
  BlockOnSlab b(interface(true), {});
  ASSERT_TRUE(b.run_until(settled));
  b.print("settled");
  const auto [n, s] = b.tie_forces();
  // The bounce is damped to 1e-7 of the weight by 30 ms (the prints); the shear forces
  // (Poisson's effect) are antisymmetric about the middle and cancel to round-off.
  EXPECT_NEAR(n / weight, 1.0, 1e-5);
  EXPECT_NEAR(s / weight, 0.0, 1e-9);
  EXPECT_EQ(b.ties->counts().intact, b.ties->n_ties());
  for (const Tie& t : b.ties->get_ties())
  {
    EXPECT_GT(t.forces.normal_force, 0.0);
    EXPECT_LT(std::abs(t.forces.shear_force), tan_phi * t.forces.normal_force);
  }
  // Settlement: m g over the slab's vertical stiffness, E' W / D = 60e9 x 2 / 1 = 1.2e11 N/m
  // if it were laterally confined, and the ties' 2 p = 1e12 N/m in series: 4.9e-7 m. The free
  // sides make the slab softer: 6.4e-7 m.
  const double confined = weight * (depth / (60e9 * width) + 1.0 / (2.0 * tie_stiffness));
  EXPECT_LT(b.displacement().y(), -confined);
  EXPECT_GT(b.displacement().y(), -2.0 * confined);
  EXPECT_LT(std::abs(b.velocity().y()), 1e-6);
}

/// A horizontal load of half the friction limit: the block stays where it is, the ties stay
/// locked and intact and hold exactly the energy that crossed into them.
TEST(FrictionalInterface, BlockSticksBelowTheFrictionLimit)
{
  const double force = 0.5 * tan_phi * weight; // [N]
  BlockOnSlab b(interface(true), {horizontal(force, {settled, settled + 0.01}, {0.0, 1.0})});
  ASSERT_TRUE(b.run_until(0.08));
  b.print("stuck");
  EXPECT_EQ(b.ties->counts().intact, b.ties->n_ties()); // none ever slid
  const auto [n, s] = b.tie_forces();
  EXPECT_NEAR(n / weight, 1.0, 1e-5);
  EXPECT_NEAR(s / force, 1.0, 1e-5); // S > 0: the ties drag the far field along +x
  // Elastic: the slab in simple shear, G W / D = 20e9 x 2 / 1 = 4e10 N/m, and the ties' shear
  // springs 2 p_s = 4e11 N/m in series: 0.41 um. The free sides carry no shear, which makes
  // the slab softer (0.69 um): within a factor 3 of it, where sliding would move it by mm.
  const double simple_shear = force * (depth / (20e9 * width) + 1.0 / (0.8 * tie_stiffness));
  EXPECT_GT(b.displacement().x(), simple_shear);
  EXPECT_LT(b.displacement().x(), 3.0 * simple_shear);
  EXPECT_LT(std::abs(b.velocity().x()), 1e-6);
  // Linear springs: the trapezoidal work on them is exact, so the tie energy is what the
  // springs hold (1.7e-3 J) and nothing is dissipated; what is left is the round-off of the
  // difference of the works on either side (0.03 J each, summed over 800 steps): 4e-12 J.
  EXPECT_GT(b.ties->tie_energy(), 0.0);
  EXPECT_NEAR(b.friction_dissipation(), 0.0, 1e-6 * b.elastic_tie_energy());
}

/// 1.5 times the friction limit: every tie slides with S = mu N and the block accelerates at
/// (F - mu m g) / m = mu g / 2 = 2.832 m/s^2; the ties dissipate mu m g per metre of slip.
/// (At twice the limit the inertia force, 0.5 m above the base, unloads the leading tie to
/// zero: it opens. The stopping test below has that.)
TEST(FrictionalInterface, BlockSlidesAboveTheFrictionLimit)
{
  const double force = 1.5 * tan_phi * weight; // [N]
  BlockOnSlab b(interface(true), {horizontal(force, {settled, settled + 0.01}, {0.0, 1.0})});
  const double t1 = 0.05, t2 = 0.1; // a window of full load [s]
  ASSERT_TRUE(b.run_until(t1));
  b.print("sliding");
  const double v1 = b.velocity().x(), x1 = b.displacement().x();
  const double d1 = b.friction_dissipation(), w1 = b.system.energy().work_of_ties;
  const double far1 = b.ties->work_on_far_field();
  ASSERT_TRUE(b.run_until(t2));
  b.print("sliding");
  const double v2 = b.velocity().x(), x2 = b.displacement().x();
  const double d2 = b.friction_dissipation(), w2 = b.system.energy().work_of_ties;
  const double far2 = b.ties->work_on_far_field();

  EXPECT_EQ(b.ties->counts().slide, b.ties->n_ties());
  // Sliding along +x, the block moves along the ties' +t relative to the slab: S > 0, the
  // friction -S t on the block opposes the motion and +S t drags the far field along. The
  // force the step applied (on the far field, F = (S, -N) on this horizontal base) is the
  // limit at the previous step's normal force (DDA's one-step lag): N changes by less than
  // 1e-5 per step in steady sliding (the prints show 5 digits of agreement).
  const std::vector<double> applied = b.far_field->spring_forces();
  for (std::size_t k = 0; k < b.ties->n_ties(); ++k)
  {
    const Tie& t = b.ties->get_ties()[k];
    EXPECT_GT(t.forces.normal_force, 0.0);
    EXPECT_NEAR(t.forces.shear_force, tan_phi * t.forces.normal_force,
                1e-12 * t.forces.normal_force);
    EXPECT_NEAR(applied[2 * k], tan_phi * t.forces.normal_force, 1e-3 * t.forces.normal_force);
    EXPECT_NEAR(applied[2 * k + 1], -t.forces.normal_force, 1e-9 * t.forces.normal_force);
  }
  const auto [n, s] = b.tie_forces();
  EXPECT_NEAR(n / weight, 1.0, 1e-4);
  EXPECT_NEAR(s / (tan_phi * weight), 1.0, 1e-4);

  // The block's translation is exact for constant forces: what departs from mu g / 2 is the
  // normal force's bounce about m g (< 1e-4 of it once sliding, the prints) and the lag, which
  // change the friction by 1e-4 of mu m g, 2e-4 of F - mu m g.
  const double expected = (force - tan_phi * weight) / mass;
  const double a = (v2 - v1) / (t2 - t1);
  std::printf("acceleration %.6f m/s^2, expected %.6f m/s^2 (%.2e off)\n", a, expected,
              a / expected - 1.0);
  EXPECT_NEAR(a / expected, 1.0, 1e-3);
  // Friction dissipates mu N per unit slip: the tie energy grows by mu m g (x2 - x1) (the
  // ties' elastic energy stays constant at constant forces), to the same 1e-4.
  std::printf("friction dissipation %.6g J over the window, mu m g dx = %.6g J\n", d2 - d1,
              tan_phi * weight * (x2 - x1));
  EXPECT_GT(d1, 0.0);
  EXPECT_NEAR((d2 - d1) / (tan_phi * weight * (x2 - x1)), 1.0, 1e-3);
  // It is the energy that left the blocks through the ties (work_of_ties decreases by it);
  // the far field, in steady shear, takes none of it (its balance holds to round-off).
  EXPECT_NEAR((w1 - w2) / (d2 - d1), 1.0, 1e-4);
  EXPECT_LT(std::abs(far2 - far1), 1e-4 * (d2 - d1));
  const fem::EnergyBalance f = b.far_field->energy();
  EXPECT_NEAR(f.dissipated, 0.0, 1e-9 * f.stored());
  // The blocks' balance: the trapezoidal rule conserves energy but in the first step (it
  // starts from a zero acceleration under gravity: 5e-4 J) and for updated geometry's
  // linearisation about the step start.
  const dda::EnergyBalance e = b.system.energy();
  std::printf("blocks: work of loads %.6g J, of ties %.6g J, kinetic %.6g J, residual %.3g J\n",
              e.work_of_loads, e.work_of_ties, e.kinetic, e.dissipated);
  EXPECT_LT(std::abs(e.dissipated), 1e-5 * e.work_of_loads);
}

/// Twice the friction limit, then the load is removed: the block decelerates at mu g, stops
/// where a rigid block would and stays there (slide -> lock with the shear the ties held while
/// sliding; the leading tie, opened by the inertia force while the load acted, closes again).
TEST(FrictionalInterface, SlidingBlockStopsWhenUnloaded)
{
  const double force = 2.0 * tan_phi * weight; // [N]
  // Full load from 40 to 60 ms, removed over 1 ms.
  BlockOnSlab b(interface(true),
                {horizontal(force, {settled, settled + 0.01, 0.06, 0.061}, {0.0, 1.0, 1.0, 0.0})});
  const double t1 = 0.065, t2 = 0.08; // decelerating [s]
  ASSERT_TRUE(b.run_until(0.05));
  b.print("pushed");
  EXPECT_EQ(b.ties->counts().slide + b.ties->counts().open, b.ties->n_ties());
  ASSERT_TRUE(b.run_until(t1));
  const double v1 = b.velocity().x();
  ASSERT_TRUE(b.run_until(t2));
  const double v2 = b.velocity().x();
  // As for the acceleration above: 1e-4 of mu m g in the friction.
  const double a = (v2 - v1) / (t2 - t1);
  std::printf("deceleration %.6f m/s^2, expected %.6f m/s^2 (%.2e off)\n", a, -tan_phi * gravity,
              a / (-tan_phi * gravity) - 1.0);
  EXPECT_NEAR(a / (-tan_phi * gravity), 1.0, 1e-3);

  // A rigid block, in units of mu g [m/s^2]: it slides once F > mu m g (from 35 ms), with
  // a / (mu g) = 200 (t - 0.035) to 40 ms, 1 to 60 ms, 1 - 2000 (t - 0.06) to 61 ms and -1 until
  // it stops: v (61 ms) = 0.0225, x (61 ms) = 2.7683e-4, a stop at 83.5 ms at 5.3e-4 (3.0 mm).
  // The model starts sliding a little later than at F = mu m g (the ties reach their limit one
  // after another from the edges over the ramp): 0.5% further: within 1%.
  const double x_stop = tan_phi * gravity * (2.7683e-4 + 0.5 * 0.0225 * 0.0225);
  ASSERT_TRUE(b.run_until(0.095));
  b.print("stopped");
  const double x_end = b.displacement().x();
  const double d_end = b.friction_dissipation();
  ASSERT_TRUE(b.run_until(0.12));
  b.print("stopped");
  std::printf("stopped at %.6e m, rigid block %.6e m (%.2e off)\n", b.displacement().x(), x_stop,
              b.displacement().x() / x_stop - 1.0);
  EXPECT_NEAR(b.displacement().x() / x_stop, 1.0, 0.01);
  // It stays: the shear springs give back the friction it stopped with, mu m g / (2 p_s +
  // slab) < 1 um, while the far field's damping settles it; then nothing moves.
  EXPECT_NEAR(b.displacement().x(), x_end, 1e-7);
  EXPECT_LT(std::abs(b.velocity().x()), 1e-6);
  const TieCounts c = b.ties->counts();
  EXPECT_EQ(c.slide, 0u);
  EXPECT_EQ(c.open, 0u);
  EXPECT_EQ(c.lock, b.ties->n_ties()); // locked again, no longer intact
  // All the work of the load went into friction but the block's and the springs' energies
  // (< 0.1 J, the far field's): the dissipation is mu m g x_stop (to 1e-4 while sliding, and
  // less than 1 um of elastic displacement) and stopped growing with the block.
  const dda::EnergyBalance e = b.system.energy();
  std::printf("work of the load %.6g J, friction dissipation %.6g J, mu m g x = %.6g J\n",
              e.work_of_loads, b.friction_dissipation(), tan_phi * weight * b.displacement().x());
  EXPECT_NEAR(b.friction_dissipation() / (tan_phi * weight * b.displacement().x()), 1.0, 1e-3);
  EXPECT_NEAR(b.friction_dissipation(), d_end, 1e-6 * d_end);
}

/// A pull of 1.5 m g at the centroid: the ties (no tensile strength) open and the block lifts
/// off at (F - m g) / m = g / 2.
TEST(FrictionalInterface, PullLargerThanTheWeightOpensTheTies)
{
  const double force = 1.5 * weight; // [N]
  BlockOnSlab b(interface(true), {load({0.5 * width, 0.5 * height}, {0.0, force},
                                       {settled, settled + dt}, {0.0, 1.0})});
  ASSERT_TRUE(b.run_until(settled));
  const double held = b.elastic_tie_energy();
  ASSERT_TRUE(b.run_until(settled + 0.005));
  b.print("lifting");
  EXPECT_EQ(b.ties->counts().open, b.ties->n_ties());
  const double t1 = b.system.time(), v1 = b.velocity().y();
  const double work_on_blocks = b.ties->work_on_blocks();
  const double work_on_far_field = b.ties->work_on_far_field();
  ASSERT_TRUE(b.run_until(settled + 0.03));
  b.print("lifting");
  EXPECT_EQ(b.ties->counts().open, b.ties->n_ties());
  EXPECT_EQ(b.tie_forces().first, 0.0);
  // Open ties carry nothing: the centroid's acceleration is exact but for round-off and the
  // block's ringing after the release seen by a monitor that follows the centroid to second
  // order in the step's increments (1e-8 measured).
  const double a = (b.velocity().y() - v1) / (b.system.time() - t1);
  const double expected = (force - weight) / mass;
  std::printf("lift-off acceleration %.9f m/s^2, expected %.9f m/s^2\n", a, expected);
  EXPECT_NEAR(a / expected, 1.0, 1e-6);
  // No work crosses open ties.
  EXPECT_EQ(b.ties->work_on_blocks(), work_on_blocks);
  EXPECT_EQ(b.ties->work_on_far_field(), work_on_far_field);
  // Opening releases the springs' compression within a step: the trapezoidal work of a force
  // that drops to zero over the step credits half of it over the whole opening displacement,
  // which is more than the springs held; the excess (the tie energy turns negative) is a
  // fraction of what they held (N^2 / (2 p): 1.4e-3 J).
  std::printf("tie energy %.6g J before opening, %.6g J after\n", held, b.ties->tie_energy());
  EXPECT_LT(std::abs(b.ties->tie_energy()), held);
}

/// The open-close remedy of the blocks' contacts holds for the ties too (they change state in
/// the same iteration): from the third iteration on, a tie that carries at most `negligible`
/// before and after changes without holding the iteration back (counted as ignored); a tie
/// carrying more, or any tie in iterations 1 and 2, holds it back. A trial lifting the settled
/// block by 1 mm opens every tie, each of which carried its share of m g.
TEST(FrictionalInterface, TiesCarryingAlmostNothingChangeWithoutHoldingTheIteration)
{
  BlockOnSlab b(interface(true), {});
  ASSERT_TRUE(b.run_until(settled));
  const std::size_t m = b.ties->n_ties();
  ASSERT_GT(m, 1u);
  for (const Tie& t : b.ties->get_ties())
    ASSERT_GT(t.forces.normal_force, 0.0); // each carries part of the weight
  Eigen::VectorXd lift = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(2 * m));
  for (std::size_t k = 0; k < m; ++k)
    lift(static_cast<Eigen::Index>(2 * k + 1)) = 1e-3; // [m], up
  const Eigen::VectorXd at_rest = Eigen::VectorXd::Zero(lift.size());
  // (iteration, negligible [N]) -> (changes that hold the iteration, changes ignored)
  const auto trial = [&](unsigned iteration, double negligible)
  {
    EXPECT_TRUE(b.ties->begin_step(dt, at_rest).taken); // trial states from the accepted ones
    std::size_t ignored = 0;
    const std::size_t holding = b.ties->update_trial_states(lift, iteration, negligible, ignored);
    return std::make_pair(holding, ignored);
  };
  EXPECT_EQ(trial(3, 0.0), std::make_pair(m, std::size_t{0}));           // they carried m g / n
  EXPECT_EQ(trial(3, 10.0 * weight), std::make_pair(std::size_t{0}, m)); // negligible
  EXPECT_EQ(trial(2, 10.0 * weight), std::make_pair(m, std::size_t{0})); // too early to ignore
  EXPECT_EQ(b.ties->counts().open, 0u); // trials only: the accepted states are unchanged
}

/// The default interface (infinite strength) under the load that slides the frictional one
/// and a pull of 1.5 m g: the ties hold in shear and tension, linear springs.
TEST(FrictionalInterface, BondedInterfaceNeverSlidesNorOpens)
{
  const double force = 2.0 * tan_phi * weight; // [N]
  BlockOnSlab b(interface(false), {horizontal(force, {settled, settled + 0.01}, {0.0, 1.0}),
                                   load({0.5 * width, 0.5 * height}, {0.0, 1.5 * weight},
                                        {settled, settled + 0.01}, {0.0, 1.0})});
  ASSERT_TRUE(b.run_until(0.08));
  b.print("bonded");
  EXPECT_EQ(b.ties->counts().intact, b.ties->n_ties());
  const auto [n, s] = b.tie_forces();
  EXPECT_NEAR(n / weight, -0.5, 1e-5); // in tension
  EXPECT_NEAR(s / force, 1.0, 1e-5);
  // Elastic, as in the stuck test (the pull makes no shear).
  const double simple_shear = force * (depth / (20e9 * width) + 1.0 / (0.8 * tie_stiffness));
  EXPECT_GT(b.displacement().x(), simple_shear);
  EXPECT_LT(b.displacement().x(), 3.0 * simple_shear);
  // Lifted by the elastic stretch of the ties and the slab only (0.3 um).
  EXPECT_GT(b.displacement().y(), 0.0);
  EXPECT_LT(b.displacement().y(), 1e-6);
  EXPECT_GT(b.ties->tie_energy(), 0.0);
  EXPECT_NEAR(b.friction_dissipation(), 0.0, 1e-6 * b.elastic_tie_energy());
}

/// Finite strength that is never reached takes the nonlinear path (trial states evaluated each
/// iteration, the constant forces F0 of locked ties carried from step to step) but must give
/// the bonded interface's answer to round-off.
TEST(FrictionalInterface, StrongInterfaceMatchesBonded)
{
  const std::vector<dda::PointLoad> loads = {
      horizontal(2.0 * tan_phi * weight, {settled, settled + 0.01}, {0.0, 1.0})};
  BlockOnSlab bonded(interface(false), loads);
  InterfaceDescription strong = interface(true);
  strong.cohesion = 1e9;         // [Pa]: 1e8 N per tie
  strong.tensile_strength = 1e9; // [Pa]
  BlockOnSlab b(strong, loads);
  for (double t = settled; t < 0.0801; t += 0.01)
  {
    ASSERT_TRUE(bonded.run_until(t));
    ASSERT_TRUE(b.run_until(t));
    const double scale = bonded.displacement().norm();
    EXPECT_NEAR(b.displacement().x(), bonded.displacement().x(), 1e-9 * scale) << t;
    EXPECT_NEAR(b.displacement().y(), bonded.displacement().y(), 1e-9 * scale) << t;
    // The tie energy is the difference of the works on the blocks and on the far field (each
    // about 16 times larger here), which the bonded interface takes from the far field's
    // displacements at the ties (N u) and the nonlinear path from the condensation: round-off
    // of those works, not of the tie energy, sets the scale.
    const double works =
        std::abs(bonded.ties->work_on_blocks()) + std::abs(bonded.ties->work_on_far_field());
    EXPECT_NEAR(b.ties->tie_energy(), bonded.ties->tie_energy(), 1e-9 * works);
  }
  b.print("strong");
  bonded.print("bonded");
  EXPECT_EQ(b.ties->counts().intact, b.ties->n_ties());
}

} // namespace
} // namespace ddafem::coupling
