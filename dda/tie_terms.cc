#include "dda/tie_terms.h"

#include "dda/submatrices.h"

#include <Eigen/LU>

namespace ddafem::dda
{
namespace
{
/// L(d) of T's last four columns (r0, ex, ey, gxy): T(x) d = (u0, v0) + L(d) (x - centroid).
Eigen::Matrix2d gradient_of(const Eigen::Vector4d& d)
{
  Eigen::Matrix2d l;
  l << d[1], 0.5 * d[3] - d[0], //
      0.5 * d[3] + d[0], d[2];
  return l;
}

/// The (r0, ex, ey, gxy) of a 2 x 2 gradient: gradient_of's inverse.
Eigen::Vector4d parameters_of(const Eigen::Matrix2d& l)
{
  return {0.5 * (l(1, 0) - l(0, 1)), l(0, 0), l(1, 1), l(0, 1) + l(1, 0)};
}

/// R^T X S for R, S the identity but for their last 4 x 4 blocks (block_turn).
Matrix6 turned(const Matrix6& x, const Matrix6& r, const Matrix6& s)
{
  Matrix6 out;
  out.leftCols<2>() = x.leftCols<2>();
  out.rightCols<4>().noalias() = x.rightCols<4>() * s.bottomRightCorner<4, 4>();
  out.bottomRows<4>() = (r.bottomRightCorner<4, 4>().transpose() * out.bottomRows<4>()).eval();
  return out;
}
} // namespace

Matrix6 block_turn(const std::vector<Point>& reference, const Point& reference_centroid,
                   const std::vector<Point>& current, const Point& current_centroid)
{
  // F = (sum r r0^T) (sum r0 r0^T)^-1 over the vertices' offsets r0 (reference), r (current).
  Eigen::Matrix2d a = Eigen::Matrix2d::Zero(), b = Eigen::Matrix2d::Zero();
  for (std::size_t k = 0; k < reference.size(); ++k)
  {
    const Vector2 r0 = reference[k] - reference_centroid;
    a.noalias() += (current[k] - current_centroid) * r0.transpose();
    b.noalias() += r0 * r0.transpose();
  }
  const Eigen::Matrix2d f = a * b.inverse();
  Matrix6 turn = Matrix6::Identity();
  for (int j = 0; j < 4; ++j)
    turn.block<4, 1>(2, 2 + j) = parameters_of(gradient_of(Eigen::Vector4d::Unit(j)) * f);
  return turn;
}

void TieTerms::set_points(const std::vector<MaterialPoint>& points)
{
  tie_runs.clear();
  for (std::size_t k = 0; k < points.size(); ++k)
    if (tie_runs.empty() || tie_runs.back().block != points[k].block)
      tie_runs.push_back({points[k].block, static_cast<Eigen::Index>(k), 1});
    else
      ++tie_runs.back().count;
  const std::size_t n = tie_runs.size();
  pair_start.resize(n);
  for (std::size_t a = 0, offset = 0; a < n; offset += n - a, ++a)
    pair_start[a] = offset;
  pairs.resize(n * (n + 1) / 2);
  stacks.resize(n);
  initial_stacks.clear();
  initial_pairs.clear();
  turns.resize(n);
}

void TieTerms::stack(const std::vector<Matrix26>& t,
                     std::vector<Eigen::Matrix<double, Eigen::Dynamic, 6>>& out) const
{
  out.resize(tie_runs.size());
  for (std::size_t r = 0; r < tie_runs.size(); ++r)
  {
    const TieRun& run = tie_runs[r];
    out[r].resize(2 * run.count, 6);
    for (Eigen::Index k = 0; k < run.count; ++k)
      out[r].middleRows<2>(2 * k) = t[static_cast<std::size_t>(run.first + k)];
  }
}

void TieTerms::direct(const Eigen::MatrixXd& h,
                      const std::vector<Eigen::Matrix<double, Eigen::Dynamic, 6>>& t,
                      std::vector<Matrix6>& out, const Parallel& parallel)
{
  // Y(:, r) = H(:, points of r) T_r, and the pair a <= b gains X = T_a^T Y(points of a,
  // columns of b). H is symmetric, so the columns of run b need only the rows of the runs up to
  // b: half of H is read, in products of whole runs.
  const std::size_t n_runs = tie_runs.size();
  const Eigen::Index m2 = h.rows();
  products.resize(m2, static_cast<Eigen::Index>(6 * n_runs));
  parallel.for_chunks(n_runs, 1,
                      [&](std::size_t begin, std::size_t end)
                      {
                        for (std::size_t r = begin; r < end; ++r)
                        {
                          const TieRun& run = tie_runs[r];
                          const Eigen::Index rows = 2 * (run.first + run.count);
                          products.block(0, static_cast<Eigen::Index>(6 * r), rows, 6).noalias() =
                              h.block(0, 2 * run.first, rows, 2 * run.count) * t[r];
                        }
                      });
  out.resize(pairs.size());
  parallel.for_chunks(n_runs, 1,
                      [&](std::size_t begin, std::size_t end)
                      {
                        for (std::size_t a = begin; a < end; ++a)
                          for (std::size_t b = a; b < n_runs; ++b)
                            out[pair_start[a] + b - a] =
                                t[a].transpose() * products.block(2 * tie_runs[a].first,
                                                                  static_cast<Eigen::Index>(6 * b),
                                                                  2 * tie_runs[a].count, 6);
                      });
}

void TieTerms::compute(const Eigen::MatrixXd& h, const std::optional<std::uint64_t> id,
                       const std::vector<Matrix26>& t, const std::vector<MaterialPoint>& points,
                       const std::vector<Block>& blocks, const bool small_displacement,
                       const Parallel& parallel)
{
  stack(t, stacks);
  if (!id)
  {
    direct(h, stacks, pairs, parallel);
    return;
  }
  // A block whose vertex list changed since t = 0 has no turn from its initial geometry.
  for (const TieRun& run : tie_runs)
    if (blocks[run.block].vertices.size() != blocks[run.block].initial_vertices.size())
    {
      direct(h, stacks, pairs, parallel);
      return;
    }
  std::vector<Matrix6>* initial = initial_pairs.use(*id);
  if (initial == nullptr)
  {
    if (initial_stacks.empty())
    {
      std::vector<Matrix26> t0(points.size());
      for (std::size_t k = 0; k < points.size(); ++k)
        t0[k] = displacement_matrix(blocks[points[k].block].initial_centroid, points[k].initial);
      stack(t0, initial_stacks);
    }
    auto x0 = std::make_unique<std::vector<Matrix6>>();
    direct(h, initial_stacks, *x0, parallel);
    initial = &initial_pairs.insert(*id, std::move(x0));
    ++initial_builds;
  }
  const std::size_t n_runs = tie_runs.size();
  for (std::size_t r = 0; r < n_runs; ++r)
  {
    const Block& b = blocks[tie_runs[r].block];
    turns[r] = small_displacement ? Matrix6::Identity().eval()
                                  : block_turn(b.initial_vertices, b.initial_centroid, b.vertices,
                                               b.moments.centroid);
  }
  const std::vector<Matrix6>& x0 = *initial;
  parallel.for_chunks(n_runs, 1,
                      [&](std::size_t begin, std::size_t end)
                      {
                        for (std::size_t a = begin; a < end; ++a)
                          for (std::size_t b = a; b < n_runs; ++b)
                            pairs[pair_start[a] + b - a] =
                                turned(x0[pair_start[a] + b - a], turns[a], turns[b]);
                      });
}

Vector6 TieTerms::force(const std::size_t a, const Eigen::VectorXd& g) const
{
  const TieRun& run = tie_runs[a];
  return stacks[a].transpose() * g.segment(2 * run.first, 2 * run.count);
}

} // namespace ddafem::dda
