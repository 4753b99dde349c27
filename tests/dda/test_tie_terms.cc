// TieSet::add_terms: a tied body's stiffness H (2m x 2m, dense) and force g (2m) over its m
// tie points enter the blocks' equations as T^T H T and T^T g, T the points' 2 x 6 displacement
// matrices. The points come in runs of consecutive points on one block, in any order; the step
// must not depend on that order.
#include "dda/submatrices.h"
#include "dda/system.h"
#include "tests/dda/step_parts.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
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
  StepResult begin_step(double, const Eigen::VectorXd&) override { return {}; }
  const Eigen::MatrixXd& stiffness() const override { return h; }
  const Eigen::VectorXd& force() const override { return g; }
  std::size_t update_trial_states(const Eigen::VectorXd&, unsigned, double, std::size_t&) override
  {
    return 0;
  }
  StepResult end_step(const Eigen::VectorXd&) override { return {}; }
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
  const StepStatus status = s.advance(m.time.dt, step_parts::of_call(s, 0));
  EXPECT_EQ(status.outcome, StepOutcome::success) << status.message;
  Eigen::VectorXd v(12);
  v << s.blocks().list[0].velocity, s.blocks().list[1].velocity;
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
  // TieSet::add_terms computes H T and the blocks' terms run by run on the threads: four runs
  // (interleaved points) on one and on two threads give the same step, bit for bit.
  std::srand(11);
  const Eigen::MatrixXd r = Eigen::MatrixXd::Random(8, 8);
  const Eigen::MatrixXd h = 1e9 * (r * r.transpose() / 8.0 + Eigen::MatrixXd::Identity(8, 8));
  const Eigen::VectorXd g = 1e6 * Eigen::VectorXd::Random(8);
  const Eigen::VectorXd one = step_with({0, 2, 1, 3}, h, g, 1);
  ASSERT_GT(one.norm(), 0.0);
  EXPECT_TRUE(step_with({0, 2, 1, 3}, h, g, 2) == one);
}

namespace
{
/// Moves block b and its points by the increment d as a step does: the points first, by T of
/// the configuration before the update, then the block.
void move(Block& b, std::vector<MaterialPoint>& points, const Vector6& d)
{
  for (MaterialPoint& p : points)
    p.position += displacement_at(b.moments.centroid, p.position, d);
  b.apply_increment(d, Eigen::Matrix3d::Identity(), false);
}
} // namespace

TEST(TieTerms, ABlockTurnMapsTheInitialTOntoTheCurrentOne)
{
  // A pentagon moved over 40 steps by rotations (0.6 rad in all), strains and translations:
  // T at each moved point equals T at its initial point times the block's turn, to round-off.
  Block b(0, {{0, 0}, {2, 0}, {2.5, 1}, {1, 2}, {-0.5, 1}});
  std::vector<MaterialPoint> points = {{0, Point(1.0, 0.0), Point(1.0, 0.0)},
                                       {0, Point(2.25, 0.5), Point(2.25, 0.5)},
                                       {0, Point(0.7, 0.9), Point(0.7, 0.9)}};
  Vector6 d;
  d << 0.01, -0.02, 0.015, 2e-4, -1e-4, 3e-4;
  for (int step = 0; step < 40; ++step)
    move(b, points, d);
  const Matrix6 turn =
      block_turn(b.initial_vertices, b.initial_centroid, b.vertices, b.moments.centroid);
  for (const MaterialPoint& p : points)
  {
    const Matrix26 now = displacement_matrix(b.moments.centroid, p.position);
    const Matrix26 turned = displacement_matrix(b.initial_centroid, p.initial) * turn;
    EXPECT_LE((now - turned).norm(), 1e-13 * now.norm());
  }
  EXPECT_GT((turn - Matrix6::Identity()).norm(), 0.5); // it did turn
}

TEST(TieTerms, TermsTurnedFromTheInitialGeometryEqualTheDirectOnes)
{
  // Two blocks with three and two tie points, moved and turned; H dense and SPD. The terms kept
  // for H's id and turned agree with T^T H T computed from the points' T now, and a second call
  // with the same id builds nothing new.
  std::vector<Block> blocks = {Block(0, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}),
                               Block(0, {{3, 0}, {4, 0}, {4, 1}, {3, 1}})};
  std::vector<MaterialPoint> points = {{0, Point(0.0, 0.5), Point(0.0, 0.5)},
                                       {0, Point(0.5, 0.0), Point(0.5, 0.0)},
                                       {0, Point(1.0, 0.2), Point(1.0, 0.2)},
                                       {1, Point(3.0, 0.5), Point(3.0, 0.5)},
                                       {1, Point(3.5, 1.0), Point(3.5, 1.0)}};
  std::srand(5);
  const Eigen::MatrixXd r = Eigen::MatrixXd::Random(10, 10);
  const Eigen::MatrixXd h = 1e9 * (r * r.transpose() / 10.0 + Eigen::MatrixXd::Identity(10, 10));
  Vector6 d0, d1;
  d0 << 0.02, 0.01, 0.3, 1e-3, -2e-3, 5e-4;
  d1 << -0.01, 0.03, -0.2, 0.0, 1e-3, -1e-3;
  std::vector<MaterialPoint> on_0(points.begin(), points.begin() + 3),
      on_1(points.begin() + 3, points.end());
  move(blocks[0], on_0, d0);
  move(blocks[1], on_1, d1);
  std::copy(on_0.begin(), on_0.end(), points.begin());
  std::copy(on_1.begin(), on_1.end(), points.begin() + 3);
  std::vector<Matrix26> t;
  for (const MaterialPoint& p : points)
    t.push_back(displacement_matrix(blocks[p.block].moments.centroid, p.position));
  const Parallel serial(1);
  TieTerms direct, kept;
  direct.set_points(points);
  kept.set_points(points);
  direct.compute(h, std::nullopt, t, points, blocks, false, serial);
  kept.compute(h, 7, t, points, blocks, false, serial);
  kept.compute(h, 7, t, points, blocks, false, serial);
  EXPECT_EQ(kept.n_initial_builds(), 1u);
  ASSERT_EQ(kept.runs().size(), 2u);
  for (std::size_t a = 0; a < 2; ++a)
    for (std::size_t b = a; b < 2; ++b)
      EXPECT_LE((kept.pair(a, b) - direct.pair(a, b)).norm(), 1e-12 * direct.pair(a, b).norm())
          << a << b;
}
