#include "dda/tie_set.h"

#include "common/input_error.h"
#include "common/stopwatch.h"
#include "dda/geometry.h"
#include "dda/step_equations.h"

#include <algorithm>
#include <sstream>

namespace ddafem::dda
{
void TieSet::attach(TiedBody& body_, const std::vector<MaterialPoint>& points_,
                    const std::vector<Block>& all_blocks, const double tolerance)
{
  blocks.clear();
  for (const MaterialPoint& p : points_)
  {
    if (p.block >= all_blocks.size() || locate_point(all_blocks[p.block].vertices, p.position,
                                                     tolerance) != PointLocation::on_boundary)
    {
      std::ostringstream s;
      s << "tie point (" << p.position.x() << ", " << p.position.y() << ") is not on the boundary "
        << "of block " << p.block << ": expected points on the blocks' outer edges";
      throw InputError(s.str());
    }
    blocks.push_back(p.block);
  }
  std::sort(blocks.begin(), blocks.end());
  blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
  // Runs of consecutive tie points on one block (FarFieldTies places each block's points
  // together: one run per tie block).
  pairs.set_points(points_);
  body = &body_;
  points = points_;
  origins.clear();
  for (const MaterialPoint& p : points)
    origins.push_back(p.position);
  matrices.resize(points.size());
}

std::vector<std::pair<std::size_t, std::size_t>> TieSet::block_pairs() const
{
  std::vector<std::pair<std::size_t, std::size_t>> out;
  out.reserve(blocks.size() * blocks.size() / 2);
  for (std::size_t i = 0; i < blocks.size(); ++i)
    for (std::size_t j = i + 1; j < blocks.size(); ++j)
      out.emplace_back(blocks[i], blocks[j]);
  return out;
}

void TieSet::measure_from_here()
{
  for (std::size_t k = 0; k < points.size(); ++k)
    origins[k] = points[k].position;
}

std::future<StepResult> TieSet::begin_step(double dt, const ElementHost& host, double& seconds)
{
  if (!body)
    return {};
  Eigen::VectorXd displacements(2 * points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
  {
    matrices[k] = host.point_matrix(points[k]);
    displacements.segment<2>(2 * k) = points[k].position - origins[k];
  }
  // A body that cannot begin on another thread begins when the step asks for it (deferred).
  return std::async(body->begins_step_on_any_thread() ? std::launch::async : std::launch::deferred,
                    [this, dt, &seconds, displacements = std::move(displacements)]
                    {
                      const auto start = Clock::now();
                      StepResult begun = body->begin_step(dt, displacements);
                      seconds += seconds_since(start);
                      return begun;
                    });
}

void TieSet::add_terms(StepEquations& step, const ElementHost& host,
                       const std::vector<Block>& all_blocks, const Parallel& parallel)
{
  if (!body)
    return;
  const Eigen::MatrixXd& h = body->stiffness();
  const Eigen::VectorXd& g = body->force();
  const auto m = static_cast<Eigen::Index>(points.size());
  if (body->stiffness_is_block_diagonal())
  {
    // Each tie point on its own: T_k^T H_kk T_k on its block's diagonal, O(m).
    for (Eigen::Index k = 0; k < m; ++k)
    {
      const std::size_t bk = points[k].block;
      const Matrix26& tk = matrices[k];
      step.rhs.segment<6>(6 * bk).noalias() += tk.transpose() * g.segment<2>(2 * k);
      step.matrix.diagonal(bk).noalias() += tk.transpose() * h.block<2, 2>(2 * k, 2 * k) * tk;
    }
    return;
  }
  // (A + T^T H T) d = b + T^T g over the runs of tie points on one block: the blocks of runs
  // a <= b gain X_ab = T_a^T H_ab T_b (its transpose into the stored upper block when a's block
  // comes after b's; X + X^T on the diagonal for two runs on one block), computed pair by pair
  // (dda/tie_terms.h) and added to the matrix in one order: the same bits on any number of
  // threads.
  pairs.compute(h, body->stiffness_id(), matrices, points, all_blocks, host.small_displacement(),
                parallel);
  const std::vector<TieRun>& runs = pairs.runs();
  for (std::size_t a = 0; a < runs.size(); ++a)
  {
    const TieRun& ra = runs[a];
    step.rhs.segment<6>(static_cast<Eigen::Index>(6 * ra.block)).noalias() += pairs.force(a, g);
    for (std::size_t b = a; b < runs.size(); ++b)
    {
      const std::size_t bb = runs[b].block;
      const Matrix6& x = pairs.pair(a, b);
      if (b == a)
        step.matrix.diagonal(ra.block) += x;
      else if (bb == ra.block)
        step.matrix.diagonal(ra.block) += x + x.transpose();
      else if (ra.block < bb)
        step.matrix.upper(step.coupling_of(ra.block, bb)) += x;
      else
        step.matrix.upper(step.coupling_of(ra.block, bb)) += x.transpose();
    }
  }
}

Eigen::VectorXd TieSet::increments(const Eigen::VectorXd& d) const
{
  Eigen::VectorXd delta(2 * points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
    delta.segment<2>(2 * k) = matrices[k] * d.segment<6>(6 * points[k].block);
  return delta;
}

void TieSet::move_points(const ElementHost& host, const Eigen::VectorXd& d)
{
  for (MaterialPoint& p : points)
    host.move_with_block(p, d);
}

void TieSet::add_loads(const std::function<void(std::size_t, double)>& add) const
{
  if (!body)
    return;
  for (std::size_t k = 0; k < points.size(); ++k)
    add(points[k].block, body->force().segment<2>(2 * k).norm());
}

} // namespace ddafem::dda
