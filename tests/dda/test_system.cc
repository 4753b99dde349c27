// The DDA step on small models with analytic answers.
#include "dda/system.h"
#include "row_of_blocks.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace ddafem;
using namespace ddafem::dda;

using test_models::nu;
using test_models::rho;
using test_models::row_of_blocks;
using test_models::young;

namespace
{
/// A 1 m block ("top") on a 1 m block ("base") held by three fixed points, bonded by `joint`.
ModelDescription block_on_fixed_base(const JointMaterial& joint)
{
  ModelDescription m;
  m.materials.push_back({"rock", rho, young, nu});
  m.joint_materials.push_back(joint);
  m.default_joint_material = 0;
  m.blocks.push_back(
      {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 0, Vector2::Zero(), Voigt::Zero(), "base", {}});
  m.blocks.push_back(
      {{{0, 1}, {1, 1}, {1, 2}, {0, 2}}, 0, Vector2::Zero(), Voigt::Zero(), "top", {}});
  for (const Point& x : {Point(0.1, 0.1), Point(0.9, 0.1), Point(0.5, 0.9)})
    m.fixed_points.push_back({x, 0.0, TimeFunction::constant(0), TimeFunction::constant(0), ""});
  return m;
}
} // namespace

TEST(System, FindsOneJointPerSharedEdge)
{
  const System s(row_of_blocks(5, 1e12));
  ASSERT_EQ(s.bonded_joints().list.size(), 4u);
  for (const Joint& j : s.bonded_joints().list)
  {
    EXPECT_EQ(j.block_b, j.block_a + 1);
    EXPECT_NEAR(j.length, 1.0, 1e-12);
    // Normal out of a (towards b) is +x for a row along x.
    EXPECT_NEAR(j.normal().x(), 1.0, 1e-12);
  }
}

TEST(System, BondedPairStretchesAsYoungsModulusAndSpringsPredict)
{
  // Two unit blocks pulled apart by F at the outer edge midpoints. At rest each block carries
  // sxx = F / (1 m^2) and the joint's two normal springs p share F:
  //   stretch between the load points = 2 F / E (two 1 m blocks, plane stress, syy = 0)
  //                                     + F / (2 p) (joint opening).
  // p = E x 1 m makes both parts comparable. DDA's scheme with a large dt damps the
  // oscillation away (static solution).
  const double p = young * 1.0, force = 1e6;
  ModelDescription m = row_of_blocks(2, p);
  m.point_loads.push_back({{0, 0.5}, {-force, 0}, TimeFunction::constant(1.0), "left"});
  m.point_loads.push_back({{2, 0.5}, {force, 0}, TimeFunction::constant(1.0), "right"});
  m.monitors.push_back({"left", {0, 0.5}});
  m.monitors.push_back({"right", {2, 0.5}});
  m.time = {1e-3, 1.0, Integrator::dda};
  System s(m);
  for (int k = 0; k < 400; ++k)
    ASSERT_EQ(s.advance(1e-3).outcome, StepOutcome::success);

  const double stretch =
      s.sample_monitor(1).displacement.x() - s.sample_monitor(0).displacement.x();
  const double expected = 2 * force / young + force / (2 * p);
  EXPECT_NEAR(stretch, expected, 1e-4 * expected);
  for (const Block& b : s.blocks().list)
  {
    EXPECT_NEAR(b.stress[0], force, 1e-4 * force);
    EXPECT_NEAR(b.stress[1], 0.0, 1e-4 * force);
  }
  const Joint& j = s.bonded_joints().list[0];
  EXPECT_NEAR(j.points[0].normal_force + j.points[1].normal_force, force, 1e-4 * force);
  // No net force: the pair does not drift.
  EXPECT_NEAR(s.sample_monitor(0).displacement.x() + s.sample_monitor(1).displacement.x(), 0.0,
              1e-6 * expected);
}

TEST(System, BondedJointCarriesShear)
{
  // Block 1 on top of a fixed block 0, pushed sideways by F at its top: the joint's two shear
  // springs (p_s = 0.4 p each) carry F, slip = F / (2 p_s) on top of the block's shear strain.
  const double p = 1e11, force = 1e5;
  ModelDescription m = block_on_fixed_base({"bond", p, 0.4, 30.0, 1e6, 1e6, true});
  m.point_loads.push_back({{0.5, 2.0}, {force, 0}, TimeFunction::constant(1.0), ""});
  m.time = {1e-3, 1.0, Integrator::dda};
  System s(m);
  for (int k = 0; k < 400; ++k)
    ASSERT_EQ(s.advance(1e-3).outcome, StepOutcome::success);
  const Joint& j = s.bonded_joints().list[0];
  // Joint tangent runs along block a's (the base's) top edge, from (1,1) to (0,1): -x.
  EXPECT_NEAR(j.tangent().x(), -1.0, 1e-9);
  const double shear = j.points[0].shear_force + j.points[1].shear_force;
  EXPECT_NEAR(-shear, force, 1e-3 * force);
  // The top block's average shear stress is F / 1 m^2.
  EXPECT_NEAR(s.blocks().list[1].stress[2], force, 2e-2 * force);
}

TEST(System, JointBreaksInTensionAndTheBlocksSeparate)
{
  // Tensile strength 1 MPa over a 1 m joint: each end spring holds 0.5 MN; pull with 2 MN. The
  // joint breaks, the blocks then meet through frictional contacts that carry no tension, and
  // each block accelerates away at F / m = 2e6 / 2650 m/s^2.
  ModelDescription m = row_of_blocks(2, 1e12);
  m.joint_materials[0].tensile_strength = 1e6;
  m.point_loads.push_back({{0, 0.5}, {-2e6, 0}, TimeFunction::constant(1.0), ""});
  m.point_loads.push_back({{2, 0.5}, {2e6, 0}, TimeFunction::constant(1.0), ""});
  m.time = {1e-4, 1.0, Integrator::dda};
  System s(m);
  ASSERT_EQ(s.bonded_joints().list.size(), 1u);
  for (int k = 0; k < 100; ++k)
    ASSERT_EQ(s.advance(1e-4).outcome, StepOutcome::success);
  EXPECT_EQ(s.bonded_joints().list.size(), 0u);
  EXPECT_EQ(s.bonded_joints().n_broken, 1u);
  const double gap = s.blocks().list[1].displacement().x() - s.blocks().list[0].displacement().x();
  const double t = s.time();
  // Free separation from the break (within the first steps): gap ~ 2 (F/m) t^2 / 2.
  EXPECT_NEAR(gap, 2e6 / 2650.0 * t * t, 0.05 * 2e6 / 2650.0 * t * t);
  EXPECT_EQ(s.contacts().counts().lock + s.contacts().counts().slide, 0u);
}

TEST(System, JointBrokenInShearLeavesContactsThatCarryTheBlock)
{
  // A 1 m block on a fixed one, bonded by a weak joint (cohesion and tensile strength 1 kPa,
  // friction 30 deg), under gravity and pushed sideways by twice what friction holds: the joint
  // breaks in the first step, and from then on the pair meets through frictional contacts
  // that carry the block's weight while it slides at a = g tan(30 deg). (The joints' lists
  // that contact detection keeps are redone when a joint breaks: without that the pair stays
  // skipped as bonded and the block falls through the base.)
  const double g = 9.81, tan_phi = std::tan(30.0 * M_PI / 180.0), weight = rho * g;
  ModelDescription m = block_on_fixed_base({"bond", 1e11, 0.4, 30.0, 1e3, 1e3, true});
  m.gravity = Vector2(0.0, -g);
  m.point_loads.push_back(
      {{0.5, 1.5}, {2.0 * tan_phi * weight, 0}, TimeFunction::constant(1.0), ""});
  m.time = {1e-4, 1.0, Integrator::dda};
  System s(m);
  for (int k = 0; k < 500; ++k)
  {
    const StepStatus status = s.advance(1e-4);
    ASSERT_EQ(status.outcome, StepOutcome::success) << "step " << k << ": " << status.message;
  }
  EXPECT_EQ(s.bonded_joints().n_broken, 1u);
  EXPECT_GT(s.contacts().counts().slide, 0u);
  // It rests on the base: it sinks no more than the contacts' penalty allows (W / p ~ 1e-7 m).
  EXPECT_GT(s.blocks().list[1].displacement().y(), -1e-4);
  // It slides at g tan(phi) from the start: x = a t^2 / 2 (within 5 %: the first step's break).
  const double t = s.time(), expected = 0.5 * g * tan_phi * t * t;
  EXPECT_NEAR(s.blocks().list[1].displacement().x(), expected, 0.05 * expected);
}

TEST(System, JointBreakingInASmallDisplacementAnalysisIsAFailure)
{
  ModelDescription m = row_of_blocks(2, 1e12);
  m.geometry = GeometryMode::small_displacement;
  m.joint_materials[0].tensile_strength = 1e6;
  m.point_loads.push_back({{0, 0.5}, {-2e6, 0}, TimeFunction::constant(1.0), ""});
  m.point_loads.push_back({{2, 0.5}, {2e6, 0}, TimeFunction::constant(1.0), ""});
  m.time = {1e-3, 1.0, Integrator::dda};
  System s(m);
  StepStatus status;
  for (int k = 0; k < 50 && status.outcome == StepOutcome::success; ++k)
    status = s.advance(1e-3);
  EXPECT_EQ(status.outcome, StepOutcome::joint_broken);
  EXPECT_NE(status.message.find("small-displacement"), std::string::npos);
}

namespace
{
/// A bar of 10 blocks of 1 m vibrating freely (no loads) from the velocity of its fundamental
/// mode, 0.1 cos(pi x / 10) m/s at the blocks' centroids.
EnergyBalance vibrate(Integrator integrator, std::size_t n_steps, double dt, double& initial)
{
  ModelDescription m = row_of_blocks(10, 2.5e12);
  for (std::size_t i = 0; i < m.blocks.size(); ++i)
    m.blocks[i].initial_velocity =
        Vector2(0.1 * std::cos(M_PI * (static_cast<double>(i) + 0.5) / 10.0), 0.0);
  m.time = {dt, dt * static_cast<double>(n_steps), integrator};
  System s(m);
  initial = s.energy().stored();
  for (std::size_t k = 0; k < n_steps; ++k)
    EXPECT_EQ(s.advance(dt).outcome, StepOutcome::success);
  return s.energy();
}
} // namespace

TEST(System, TrapezoidalNewmarkConservesEnergy)
{
  // 2000 steps of 1e-5 s = 20 ms, several periods of the bar's fundamental mode.
  double initial = 0.0;
  const EnergyBalance e = vibrate(Integrator::newmark_trapezoidal, 2000, 1e-5, initial);
  EXPECT_GT(initial, 0.0);
  EXPECT_NEAR(e.stored(), initial, 1e-3 * initial);
  EXPECT_GT(e.strain + e.spring, 0.01 * initial); // it really vibrates
}

TEST(System, DdaSchemeDissipatesEnergy)
{
  // DDA's scheme (Newmark beta = 1/2, gamma = 1) damps a mode of frequency w by the algorithmic
  // damping ratio (gamma - 1/2) w dt / 2 (Hilber & Hughes 1978; w dt << 1): its energy decays
  // as exp(-(gamma - 1/2) w^2 dt t). The bar's fundamental mode: w = pi c / L with c =
  // sqrt(E / rho) = 4344 m/s, L = 10 m, w = 1365 rad/s (the joints' springs, 50 times the
  // blocks' axial stiffness, soften it by about 1 %): -ln(E / E0) = 0.186 over 20 ms at dt =
  // 1e-5 s, 0.093 at dt / 2 (measured 0.193 and 0.101: the higher modes the blocks' rigid
  // centroid field also excites lose faster).
  const double c = std::sqrt(young / rho), w = M_PI * c / 10.0, t = 0.02;
  for (const double dt : {1e-5, 5e-6})
  {
    double initial = 0.0;
    const EnergyBalance e =
        vibrate(Integrator::dda, static_cast<std::size_t>(std::lround(t / dt)), dt, initial);
    const double decay = -std::log(e.stored() / initial);
    EXPECT_NEAR(decay, 0.5 * w * w * dt * t, 0.1 * 0.5 * w * w * dt * t) << "dt " << dt;
    EXPECT_NEAR(e.dissipated, initial - e.stored(), 1e-9 * initial); // reported as dissipated
  }
}

TEST(System, SolversAgree)
{
  // The same loaded bar with both sparse direct solvers: identical histories to round-off.
  ModelDescription m = row_of_blocks(20, 2.5e12);
  m.point_loads.push_back({{0, 0.5}, {1e6, 0}, TimeFunction::sine_pulse(1.0, 500.0, 1, 0), ""});
  m.monitors.push_back({"m", {10.5, 0.5}});
  m.time = {1e-5, 1e-3, Integrator::dda};
  ModelDescription m2 = m;
  m2.solver.direct = SolverKind::klu;
  System a(m), b(m2);
  for (int k = 0; k < 100; ++k)
  {
    ASSERT_EQ(a.advance(1e-5).outcome, StepOutcome::success);
    ASSERT_EQ(b.advance(1e-5).outcome, StepOutcome::success);
  }
  const double sa = a.sample_monitor(0).stress[0], sb = b.sample_monitor(0).stress[0];
  EXPECT_GT(std::abs(sa), 1e3); // the pulse has arrived
  EXPECT_NEAR(sa, sb, 1e-8 * std::abs(sa));
  // The factorization is reused: geometry drifts by the strains, refinement absorbs it.
  EXPECT_LT(a.get_solver().n_factorizations(), 5u);
  EXPECT_LT(b.get_solver().n_factorizations(), 5u);
}

TEST(System, SmallDisplacementMatchesUpdatedGeometryForWaves)
{
  // A 1 MPa pulse strains the bar by 2e-5: linearising about the initial geometry changes the
  // histories by the order of that strain, while the matrix is factorized once and each step is
  // a single solve (no refinement).
  ModelDescription m = row_of_blocks(30, 2.5e12);
  m.point_loads.push_back({{0, 0.5}, {1e6, 0}, TimeFunction::sine_pulse(1.0, 500.0, 1, 0), ""});
  m.monitors.push_back({"m", {15.5, 0.5}});
  m.time = {1e-5, 4e-3, Integrator::dda};
  ModelDescription linear = m;
  linear.geometry = GeometryMode::small_displacement;
  System updated(m), small(linear);
  double max_difference = 0.0, peak = 0.0;
  for (int k = 0; k < 400; ++k)
  {
    ASSERT_EQ(updated.advance(1e-5).outcome, StepOutcome::success);
    ASSERT_EQ(small.advance(1e-5).outcome, StepOutcome::success);
    const double su = updated.sample_monitor(0).stress[0];
    max_difference = std::max(max_difference, std::abs(su - small.sample_monitor(0).stress[0]));
    peak = std::max(peak, std::abs(su));
  }
  EXPECT_GT(peak, 0.9e6);
  EXPECT_LT(max_difference, 1e-4 * peak);
  EXPECT_EQ(small.get_solver().n_factorizations(), 1u);
  EXPECT_EQ(small.get_solver().n_solves(), 400u);
  EXPECT_EQ(small.get_solver().n_refinements(), 0u);
}

TEST(System, SmallDisplacementConservesEnergyWithTrapezoidalNewmark)
{
  // The linear system M a + K u = 0 with the trapezoidal rule conserves energy exactly.
  ModelDescription m = row_of_blocks(10, 2.5e12);
  m.geometry = GeometryMode::small_displacement;
  for (std::size_t i = 0; i < m.blocks.size(); ++i)
    m.blocks[i].initial_velocity = Vector2(i < 5 ? 0.1 : -0.1, 0.0);
  m.time = {1e-5, 2e-2, Integrator::newmark_trapezoidal};
  System s(m);
  const double initial = s.energy().stored();
  for (int k = 0; k < 2000; ++k)
    ASSERT_EQ(s.advance(1e-5).outcome, StepOutcome::success);
  EXPECT_NEAR(s.energy().stored(), initial, 1e-9 * initial);
}
