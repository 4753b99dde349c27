// System::add_tie_terms: a tied body's stiffness H (2m x 2m, dense) and force g (2m) over its m
// tie points enter the blocks' equations as T^T H T and T^T g, T the points' 2 x 6 displacement
// matrices. The points come in runs of consecutive points on one block, in any order; the step
// must not depend on that order.
#include "dda/system.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <string>
#include <vector>

using namespace ddafem;
using namespace ddafem::dda;

namespace
{
/// A tied body of fixed H and g: springs between the tie points and the ground, coupled.
class SpringBody final : public TiedBody
{
public:
  SpringBody(Eigen::MatrixXd h_, Eigen::VectorXd g_) : h(std::move(h_)), g(std::move(g_)) {}
  void begin_stage(StageMode) override {}
  std::string begin_step(double, const Eigen::VectorXd&) override { return {}; }
  const Eigen::MatrixXd& stiffness() const override { return h; }
  const Eigen::VectorXd& force() const override { return g; }
  std::size_t update_trial_states(const Eigen::VectorXd&, unsigned, double, std::size_t&) override
  {
    return 0;
  }
  std::string end_step(const Eigen::VectorXd&) override { return {}; }
  double work_on_blocks() const override { return 0.0; }

private:
  Eigen::MatrixXd h;
  Eigen::VectorXd g;
};

/// Two unit blocks 2 m apart (no contact), no gravity.
ModelDescription two_blocks()
{
  ModelDescription m;
  m.materials.push_back({"rock", 2650.0, 10e9, 0.25});
  m.joint_materials.push_back({"joint", 1e10, 0.4, 30.0, 0.0, 0.0, false});
  m.default_joint_material = 0;
  BlockDescription a, b;
  a.vertices = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  b.vertices = {{3, 0}, {4, 0}, {4, 1}, {3, 1}};
  m.blocks = {a, b};
  m.time.dt = 1e-3;
  m.time.end_time = 1.0;
  return m;
}

/// The blocks' velocities (6 each) after one step with the tie points in the order `order`
/// (indices into the four points below), H and g permuted with them.
Eigen::VectorXd step_with(const std::vector<int>& order, const Eigen::MatrixXd& h,
                          const Eigen::VectorXd& g, unsigned threads = 1)
{
  const std::vector<MaterialPoint> points = {{0, Point(0.0, 0.5), Point(0.0, 0.5)},
                                             {0, Point(0.5, 0.0), Point(0.5, 0.0)},
                                             {1, Point(3.0, 0.5), Point(3.0, 0.5)},
                                             {1, Point(3.5, 1.0), Point(3.5, 1.0)}};
  Eigen::PermutationMatrix<Eigen::Dynamic> p(8); // row 2 i + c of the permuted = 2 order[i] + c
  std::vector<MaterialPoint> ordered;
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    ordered.push_back(points[static_cast<std::size_t>(order[i])]);
    for (int c = 0; c < 2; ++c)
      p.indices()[2 * order[i] + c] = static_cast<int>(2 * i) + c;
  }
  ModelDescription m = two_blocks();
  m.solver.threads = threads;
  System s(m);
  SpringBody body(p * h * p.transpose(), p * g);
  s.tie(body, ordered);
  s.begin_stage(StageMode::dynamic);
  const StepStatus status = s.advance(m.time.dt);
  EXPECT_EQ(status.outcome, StepOutcome::success) << status.message;
  Eigen::VectorXd v(12);
  v << s.get_blocks()[0].velocity, s.get_blocks()[1].velocity;
  return v;
}
} // namespace

TEST(TieTerms, TheOrderOfTheTiePointsDoesNotChangeTheStep)
{
  // A dense SPD H of 1e9 N/m (the blocks' own stiffness is 1e10 N/m) and forces of 1 MN.
  std::srand(7);
  const Eigen::MatrixXd r = Eigen::MatrixXd::Random(8, 8);
  const Eigen::MatrixXd h = 1e9 * (r * r.transpose() / 8.0 + Eigen::MatrixXd::Identity(8, 8));
  const Eigen::VectorXd g = 1e6 * Eigen::VectorXd::Random(8);
  const Eigen::VectorXd grouped = step_with({0, 1, 2, 3}, h, g);
  ASSERT_GT(grouped.norm(), 0.0);
  // Interleaved (four runs), the second block's runs first (its coupling blocks transposed),
  // and two runs on one block (0, then 1 twice, then 0 again).
  for (const std::vector<int>& order : {std::vector<int>{0, 2, 1, 3}, std::vector<int>{2, 3, 0, 1},
                                        std::vector<int>{0, 2, 3, 1}, std::vector<int>{3, 0, 1, 2}})
  {
    const Eigen::VectorXd v = step_with(order, h, g);
    EXPECT_LE((v - grouped).norm(), 1e-10 * grouped.norm())
        << "order " << order[0] << order[1] << order[2] << order[3];
  }
}

TEST(TieTerms, TwoThreadsGiveTheSameBits)
{
  // add_tie_terms computes H T and the blocks' terms run by run on the threads: four runs
  // (interleaved points) on one and on two threads give the same step, bit for bit.
  std::srand(11);
  const Eigen::MatrixXd r = Eigen::MatrixXd::Random(8, 8);
  const Eigen::MatrixXd h = 1e9 * (r * r.transpose() / 8.0 + Eigen::MatrixXd::Identity(8, 8));
  const Eigen::VectorXd g = 1e6 * Eigen::VectorXd::Random(8);
  const Eigen::VectorXd one = step_with({0, 2, 1, 3}, h, g, 1);
  ASSERT_GT(one.norm(), 0.0);
  EXPECT_TRUE(step_with({0, 2, 1, 3}, h, g, 2) == one);
}
