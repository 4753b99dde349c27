#include "dda/linear_solver.h"

#include "common/klu.h"
#include "dda/block_cholesky.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <cassert>
#include <cmath>
#include <limits>

namespace ddafem::dda
{
// ---- BlockSparseMatrix ----------------------------------------------------------------------

BlockSparseMatrix::BlockSparseMatrix(std::size_t n_blocks,
                                     std::vector<std::pair<std::size_t, std::size_t>> couplings)
    : coupling_pairs(std::move(couplings)), diagonal_blocks(n_blocks, Matrix6::Zero()),
      upper_blocks(coupling_pairs.size(), Matrix6::Zero())
{
  for (const auto& [i, j] : coupling_pairs)
  {
    (void)i;
    (void)j;
    assert(i < j && j < n_blocks);
  }
}

void BlockSparseMatrix::set_zero()
{
  for (Matrix6& m : diagonal_blocks)
    m.setZero();
  for (Matrix6& m : upper_blocks)
    m.setZero();
}

Eigen::VectorXd BlockSparseMatrix::multiply(const Eigen::VectorXd& x) const
{
  Eigen::VectorXd y;
  multiply(x, y);
  return y;
}

void BlockSparseMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const
{
  y.resize(x.size());
  for (std::size_t i = 0; i < diagonal_blocks.size(); ++i)
    y.segment<6>(6 * i) = diagonal_blocks[i] * x.segment<6>(6 * i);
  for (std::size_t k = 0; k < coupling_pairs.size(); ++k)
  {
    const auto [i, j] = coupling_pairs[k];
    y.segment<6>(6 * i) += upper_blocks[k] * x.segment<6>(6 * j);
    y.segment<6>(6 * j) += upper_blocks[k].transpose() * x.segment<6>(6 * i);
  }
}

bool BlockSparseMatrix::same_structure(const BlockSparseMatrix& other) const
{
  return n_blocks() == other.n_blocks() && coupling_pairs == other.coupling_pairs;
}

bool BlockSparseMatrix::same_values(const BlockSparseMatrix& other) const
{
  return diagonal_blocks == other.diagonal_blocks && upper_blocks == other.upper_blocks;
}

namespace
{
// ---- Eigen sparse Cholesky (LDL^T) ----------------------------------------------------------

/// Eigen's SimplicialLDLT on the upper triangle, with AMD ordering. The CSC structure is built
/// once; each factorization copies the block values through a precomputed index map.
class EigenLdltSolver final : public SparseDirectSolver
{
public:
  void analyze_pattern(const BlockSparseMatrix& a) override
  {
    // Triplets in a fixed order; remember for each entry where it lands in valuePtr().
    const std::size_t n = a.n_rows();
    std::vector<Eigen::Triplet<double>> triplets;
    for (std::size_t b = 0; b < a.n_blocks(); ++b)
      for (int c = 0; c < 6; ++c)
        for (int r = 0; r <= c; ++r)
          triplets.emplace_back(6 * b + r, 6 * b + c, 1.0);
    for (std::size_t k = 0; k < a.n_couplings(); ++k)
    {
      const auto [i, j] = a.coupling(k);
      for (int c = 0; c < 6; ++c)
        for (int r = 0; r < 6; ++r)
          triplets.emplace_back(6 * i + r, 6 * j + c, 1.0);
    }
    matrix.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    matrix.setFromTriplets(triplets.begin(), triplets.end());
    matrix.makeCompressed();
    diagonal_slots.clear();
    for (std::size_t b = 0; b < a.n_blocks(); ++b)
      for (int c = 0; c < 6; ++c)
        for (int r = 0; r <= c; ++r)
          diagonal_slots.push_back(slot(6 * b + r, 6 * b + c));
    upper_slots.clear();
    for (std::size_t k = 0; k < a.n_couplings(); ++k)
    {
      const auto [i, j] = a.coupling(k);
      for (int c = 0; c < 6; ++c)
        for (int r = 0; r < 6; ++r)
          upper_slots.push_back(slot(6 * i + r, 6 * j + c));
    }
    ldlt.analyzePattern(matrix);
  }

  bool factorize(const BlockSparseMatrix& a) override
  {
    double* values = matrix.valuePtr();
    std::size_t s = 0;
    for (std::size_t b = 0; b < a.n_blocks(); ++b)
      for (int c = 0; c < 6; ++c)
        for (int r = 0; r <= c; ++r)
          values[diagonal_slots[s++]] = a.diagonal(b)(r, c);
    s = 0;
    for (std::size_t k = 0; k < a.n_couplings(); ++k)
      for (int c = 0; c < 6; ++c)
        for (int r = 0; r < 6; ++r)
          values[upper_slots[s++]] = a.upper(k)(r, c);
    ldlt.factorize(matrix);
    if (ldlt.info() != Eigen::Success)
      return false;
    // LDL^T succeeds on indefinite matrices; the step matrix must be positive definite.
    return (ldlt.vectorD().array() > 0.0).all();
  }

  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override { x = ldlt.solve(b); }

  std::string name() const override { return name_of(SolverKind::eigen_ldlt); }

private:
  std::ptrdiff_t slot(std::size_t row, std::size_t col) const
  {
    const auto c = static_cast<Eigen::Index>(col);
    const int* inner = matrix.innerIndexPtr();
    const int begin = matrix.outerIndexPtr()[c];
    const int end = matrix.outerIndexPtr()[c + 1];
    for (int p = begin; p < end; ++p)
      if (static_cast<std::size_t>(inner[p]) == row)
        return p;
    assert(false && "entry not in pattern");
    return -1;
  }

  Eigen::SparseMatrix<double, Eigen::ColMajor, int> matrix;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double, Eigen::ColMajor, int>, Eigen::Upper> ldlt;
  std::vector<std::ptrdiff_t> diagonal_slots;
  std::vector<std::ptrdiff_t> upper_slots;
};

// ---- SuiteSparse KLU --------------------------------------------------------------------------

/// SuiteSparse KLU (sparse LU, common/klu.h) on the full symmetric matrix. Symbolic
/// factorization once, numeric factorization per change; a failed symbolic factorization makes
/// factorize() return false, a failed solve leaves x not finite (the caller checks).
class KluSolver final : public SparseDirectSolver
{
public:
  void analyze_pattern(const BlockSparseMatrix& a) override
  {
    const int n = static_cast<int>(a.n_rows());
    // Column indices per block row: itself and its coupled blocks.
    block_neighbours.assign(a.n_blocks(), {});
    for (std::size_t b = 0; b < a.n_blocks(); ++b)
      block_neighbours[b].push_back(b);
    for (std::size_t k = 0; k < a.n_couplings(); ++k)
    {
      const auto [i, j] = a.coupling(k);
      block_neighbours[i].push_back(j);
      block_neighbours[j].push_back(i);
    }
    std::vector<int> entries_per_row(static_cast<std::size_t>(n));
    for (std::size_t b = 0; b < a.n_blocks(); ++b)
      for (int r = 0; r < 6; ++r)
        entries_per_row[6 * b + static_cast<std::size_t>(r)] =
            static_cast<int>(6 * block_neighbours[b].size());
    klu.start_pattern(n, entries_per_row);
    fill(a);
    analyzed = klu.finish_pattern();
  }

  bool factorize(const BlockSparseMatrix& a) override
  {
    fill(a);
    return analyzed && klu.factorize();
  }

  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override
  {
    x.resize(b.size());
    if (!klu.solve(b.data(), x.data()))
      x.setConstant(std::numeric_limits<double>::quiet_NaN());
  }

  std::string name() const override { return name_of(SolverKind::klu); }

private:
  /// Writes the values of a into the matrix (its pattern on the first call).
  void fill(const BlockSparseMatrix& a)
  {
    std::vector<int> columns;
    std::vector<double> values;
    // Lookup of the coupling block for (i, j) in either order.
    std::vector<std::vector<std::pair<std::size_t, std::size_t>>> coupling_of(a.n_blocks());
    for (std::size_t k = 0; k < a.n_couplings(); ++k)
    {
      const auto [i, j] = a.coupling(k);
      coupling_of[i].emplace_back(j, k);
      coupling_of[j].emplace_back(i, k);
    }
    for (std::size_t bi = 0; bi < a.n_blocks(); ++bi)
      for (int r = 0; r < 6; ++r)
      {
        columns.clear();
        values.clear();
        for (int c = 0; c < 6; ++c)
        {
          columns.push_back(static_cast<int>(6 * bi) + c);
          values.push_back(a.diagonal(bi)(r, c));
        }
        for (const auto& [bj, k] : coupling_of[bi])
          for (int c = 0; c < 6; ++c)
          {
            columns.push_back(static_cast<int>(6 * bj) + c);
            // Upper block (i, j) stored for i < j; the lower block is its transpose.
            values.push_back(bi < bj ? a.upper(k)(r, c) : a.upper(k)(c, r));
          }
        klu.set_row(static_cast<int>(6 * bi) + r, columns, values);
      }
  }

  Klu klu;
  bool analyzed = false; ///< the symbolic factorization succeeded
  std::vector<std::vector<std::size_t>> block_neighbours;
};

} // namespace

std::unique_ptr<SparseDirectSolver> make_sparse_direct_solver(SolverKind kind)
{
  switch (kind)
  {
  case SolverKind::eigen_ldlt:
    return std::make_unique<EigenLdltSolver>();
  case SolverKind::klu:
    return std::make_unique<KluSolver>();
  case SolverKind::block_ldlt:
    return std::make_unique<BlockCholeskySolver>();
  }
  return nullptr;
}

// ---- FactorizationReusingSolver --------------------------------------------------------------

FactorizationReusingSolver::FactorizationReusingSolver(SolverKind kind_, double tolerance_,
                                                       unsigned max_refinements_,
                                                       std::size_t max_kept)
    : kind(kind_), tolerance(tolerance_), max_refinements(max_refinements_), kept(max_kept)
{
}

std::string FactorizationReusingSolver::name() const
{
  return name_of(kind);
}

SolveStatus FactorizationReusingSolver::factorize_and_solve(Factored& f, const BlockSparseMatrix& a,
                                                            const Eigen::VectorXd& b,
                                                            Eigen::VectorXd& x)
{
  SolveStatus status;
  if (!f.matrix)
    f.solver->analyze_pattern(a);
  ++factorization_count;
  if (!f.solver->factorize(a))
  {
    f.matrix.reset();
    status.success = false;
    status.message = "the step matrix is singular or not positive definite (" + f.solver->name() +
                     " factorization failed)";
    return status;
  }
  f.matrix = std::make_unique<BlockSparseMatrix>(a);
  f.solver->solve(b, x);
  ++solve_count;
  status.factorized = true;
  return status;
}

SolveStatus FactorizationReusingSolver::refine(Factored& f, const BlockSparseMatrix& a,
                                               const Eigen::VectorXd& b, Eigen::VectorXd& x)
{
  // Conjugate gradients on A (symmetric positive definite) preconditioned by the factors of
  // the old matrix: converges in a few iterations when A differs from it by a small or a
  // low-rank change (geometry drift, contacts changing state).
  SolveStatus status;
  const double b_norm = b.norm();
  const double target = tolerance * (b_norm > 0.0 ? b_norm : 1.0);
  f.solver->solve(b, x);
  ++solve_count;
  Eigen::VectorXd r = b - a.multiply(x);
  double r_norm = r.norm();
  Eigen::VectorXd z, p, q;
  double rz = 0.0;
  for (unsigned k = 0; r_norm > target && k < max_refinements; ++k)
  {
    f.solver->solve(r, z);
    ++solve_count;
    const double rz_new = r.dot(z);
    p = k == 0 ? z : Eigen::VectorXd(z + (rz_new / rz) * p);
    rz = rz_new;
    q = a.multiply(p);
    const double alpha = rz / p.dot(q);
    x += alpha * p;
    r -= alpha * q;
    r_norm = r.norm();
    ++refinement_count;
    ++status.n_refinements;
  }
  status.relative_residual = b_norm > 0.0 ? r_norm / b_norm : r_norm;
  if (!(r_norm <= target))
  {
    if (!f.matrix->same_structure(a))
      f.matrix.reset(); // a new structure needs a new symbolic analysis
    status = factorize_and_solve(f, a, b, x);
  }
  return status;
}

SolveStatus FactorizationReusingSolver::solve(const BlockSparseMatrix& a, const Eigen::VectorXd& b,
                                              Eigen::VectorXd& x, MatrixChange change,
                                              const double key)
{
  // `unchanged` vouches for the previous call's matrix: the factors' own only if that call
  // factorized it or found it equal to theirs, not if it refined with older factors.
  const bool previous_was_factored =
      !kept.empty() && kept.front_key() == key && last_call_used_own_factors;
  Factored* f = kept.use(key);
  if (f == nullptr)
  {
    auto made = std::make_unique<Factored>();
    made->solver = make_sparse_direct_solver(kind);
    f = &kept.insert(key, std::move(made));
  }
  SolveStatus status;
  bool own_factors = true;
  if (!f->matrix || f->matrix->n_rows() != a.n_rows())
  {
    f->matrix.reset();
    status = factorize_and_solve(*f, a, b, x);
  }
  else if (f->matrix->same_structure(a) &&
           ((previous_was_factored && change == MatrixChange::unchanged) ||
            f->matrix->same_values(a)))
  {
    f->solver->solve(b, x);
    ++solve_count;
  }
  else
  {
    status = refine(*f, a, b, x);
    own_factors = status.factorized;
  }
  last_call_used_own_factors = own_factors;
  if (status.success && !x.allFinite())
  {
    status.success = false;
    status.message = "the solution of the step contains NaN or infinity";
  }
  return status;
}

} // namespace ddafem::dda
