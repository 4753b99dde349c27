// The step's modules alone (issue 55): StepEquations' matrix structure and coupling lookup,
// StepScheme's protocol of Bathe's half steps, BlockSet's view of the blocks and StepDashpots'
// mean velocities.
#include "common/input_error.h"
#include "dda/block_set.h"
#include "dda/damping.h"
#include "dda/step_equations.h"
#include "dda/step_scheme.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

using namespace ddafem::dda;

TEST(StepEquations, CouplingOfIsTheIndexOfThePairInTheSortedList)
{
  // Random pairs (i < j) over 40 blocks: coupling_of(i, j) and coupling_of(j, i) are the pair's
  // index in the sorted list (what the matrix's upper blocks are numbered by).
  std::mt19937 random(5);
  std::uniform_int_distribution<std::size_t> block(0, 39);
  StepEquations::BlockPairs pairs;
  while (pairs.size() < 150)
  {
    const std::size_t a = block(random), b = block(random);
    if (a != b)
      pairs.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  StepEquations equations;
  ASSERT_TRUE(equations.set_couplings(40, pairs));
  EXPECT_EQ(equations.matrix.n_blocks(), 40u);
  for (std::size_t k = 0; k < pairs.size(); ++k)
  {
    EXPECT_EQ(equations.coupling_of(pairs[k].first, pairs[k].second), k);
    EXPECT_EQ(equations.coupling_of(pairs[k].second, pairs[k].first), k);
  }
}

TEST(StepEquations, KeepsTheMatrixWhileTheStructureStays)
{
  StepEquations equations;
  const StepEquations::BlockPairs pairs{{0, 1}, {1, 2}};
  EXPECT_TRUE(equations.set_couplings(3, pairs));
  EXPECT_FALSE(equations.set_couplings(3, pairs));   // the same pairs: nothing new
  EXPECT_TRUE(equations.set_couplings(4, pairs));    // a block more
  EXPECT_TRUE(equations.set_couplings(4, {{0, 1}})); // a pair fewer
  EXPECT_EQ(equations.coupling_rows, (std::vector<std::size_t>{0, 1, 1, 1, 1}));
}

TEST(StepScheme, BathesSecondHalfFollowsAFirstHalfOfTheSameDt)
{
  StepScheme scheme;
  scheme.set_up(Integrator::bathe, 0.0);
  const std::vector<Block> none;
  // Dynamic stage: no full step, and no second half before a first half of the same dt.
  EXPECT_THROW(scheme.choose(0.01, StepPart::full, true), std::logic_error);
  EXPECT_THROW(scheme.choose(0.01, StepPart::second_half, true), std::logic_error);
  // The motion starts with DDA's scheme (a and r unknown); the first half opens the pair.
  scheme.choose(0.01, StepPart::first_half, true);
  EXPECT_FALSE(scheme.second_half);
  EXPECT_EQ(scheme.coefficients.gamma, integrator_coefficients(Integrator::dda, 0.0).gamma);
  scheme.record_half(0.01, Eigen::VectorXd(), none, true);
  EXPECT_EQ(scheme.open_half, 0.01);
  EXPECT_THROW(scheme.choose(0.02, StepPart::second_half, true), std::logic_error);
  scheme.motion_starts = false;
  scheme.choose(0.01, StepPart::second_half, true);
  EXPECT_TRUE(scheme.second_half);
  EXPECT_EQ(scheme.start_force_lag(), 0.0); // backward Euler starts from velocities alone
  scheme.record_half(0.01, Eigen::VectorXd(), none, true);
  EXPECT_EQ(scheme.open_half, 0.0); // the pair is closed
  // A static stage takes every part as a full step with the scene's coefficients.
  scheme.choose(0.01, StepPart::full, false);
  EXPECT_FALSE(scheme.second_half);
  EXPECT_EQ(scheme.coefficients.alpha_f, scheme.integration.alpha_f);
}

namespace
{
/// Two 2 m x 1 m blocks of 2500 kg/m^3 side by side (x 0 to 2 and 2 to 4, y 0 to 1), the second
/// named in the scene.
ModelDescription two_blocks(GeometryMode geometry)
{
  ModelDescription m;
  m.geometry = geometry;
  m.materials = {{"rock", 2500.0, 10e9, 0.25}};
  BlockDescription left, right;
  left.vertices = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  right.vertices = {{2, 0}, {4, 0}, {4, 1}, {2, 1}};
  right.origin = "blocks[1]";
  m.blocks = {left, right};
  return m;
}

} // namespace

TEST(BlockSet, AttachesPointsAndMovesThemWithTheirBlock)
{
  const ModelDescription m = two_blocks(GeometryMode::updated);
  const BlockSet blocks(m);
  EXPECT_EQ(blocks.n_dofs(), 12u);
  EXPECT_EQ(block_names(m), (std::vector<std::string>{"block 0", "blocks[1]"}));
  MaterialPoint p = blocks.attach({3.0, 0.5}, "monitor `crown`");
  EXPECT_EQ(p.block, 1u);
  try
  {
    blocks.attach({5.0, 0.5}, "monitor `crown`");
    FAIL() << "a point outside every block was attached";
  }
  catch (const ddafem::InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("monitor `crown` at (5, 0.5) lies outside every block"),
              std::string::npos)
        << e.what();
  }
  // A rotation r0 = 0.01 rad of block 1 about its centroid (3, 0.5) moves the point 0.5 m to
  // its right by (0, 0.005) m; block 0's unknowns do not touch it.
  Eigen::VectorXd d = Eigen::VectorXd::Zero(12);
  d(2) = 1.0;
  d(6 + 2) = 0.01;
  p = blocks.attach({3.5, 0.5}, "point");
  blocks.move_with_block(p, d);
  EXPECT_NEAR(p.position.x(), 3.5, 1e-15);
  EXPECT_NEAR(p.position.y(), 0.505, 1e-15);
  // The largest vertex displacement: block 0 turned by 1 rad about (1, 0.5), its corners at
  // sqrt(1.25) m from the centroid.
  EXPECT_NEAR(blocks.largest_vertex_displacement(d), std::sqrt(1.25), 1e-12);
}

TEST(BlockSet, MassDensityAndKineticEnergyKeepTheInitialMass)
{
  for (const GeometryMode geometry : {GeometryMode::updated, GeometryMode::small_displacement})
  {
    const ModelDescription m = two_blocks(geometry);
    BlockSet blocks(m);
    EXPECT_DOUBLE_EQ(blocks.mass_of(0), 2500.0 * 2.0); // rho A0 [kg]
    // Stretch block 0 by 10 % in x: the updated geometry's density falls by as much, so that
    // rho A stays the initial mass; the small-displacement one keeps rho and A0.
    Vector6 di = Vector6::Zero();
    di(3) = 0.1;
    blocks.list[0].apply_increment(di, blocks.materials.elasticity[0],
                                   geometry == GeometryMode::small_displacement);
    const Block& b = blocks.list[0];
    EXPECT_NEAR(blocks.density(b) * blocks.linearisation_moments(b).area, 5000.0, 1e-9);
    // A translation at 2 m/s: m v^2 / 2 = 10 kJ in both.
    blocks.list[0].velocity.setZero();
    blocks.list[0].velocity(0) = 2.0;
    EXPECT_NEAR(blocks.kinetic_energy(b), 0.5 * 5000.0 * 4.0, 1e-8);
    blocks.set_at_rest();
    EXPECT_EQ(blocks.kinetic_energy(b), 0.0);
  }
}

TEST(StepDashpots, MeanVelocityIsTheMeanOfStartAndNewmarkEnd)
{
  StepDashpots dashpots;
  Eigen::VectorXd d = Eigen::VectorXd::Constant(6, 0.002);
  EXPECT_TRUE(dashpots.mean_velocities(d).empty()); // no dashpot acts: no work to add
  dashpots.velocity_factor = 1000.0;                // gamma / (beta dt) [1/s]
  dashpots.offsets = {Vector6::Constant(-1.0)};
  dashpots.start = {Vector6::Constant(0.5)};
  // v1 = 1000 x 0.002 - 1 = 1; mean (0.5 + 1) / 2 = 0.75.
  const std::vector<Vector6> mean = dashpots.mean_velocities(d);
  ASSERT_EQ(mean.size(), 1u);
  EXPECT_NEAR((mean[0] - Vector6::Constant(0.75)).norm(), 0.0, 1e-15);
}
