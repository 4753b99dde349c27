// The step's modules alone (issue 55): StepEquations' matrix structure and coupling lookup,
// and StepScheme's protocol of Bathe's half steps.
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
