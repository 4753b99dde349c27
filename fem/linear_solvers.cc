// Direct (CHOLMOD, UMFPACK, KLU) and iterative (preconditioned CG) solvers of the effective
// matrix.
#include "fem/linear_solvers.h"

#include "common/klu.h"

#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparse_direct.h>

#include <suitesparse/cholmod.h>

#include <stdexcept>
#include <vector>

namespace ddafem::fem
{
using namespace dealii;

namespace
{
class UmfpackSolver : public EffectiveSolver
{
public:
  void initialize(const SparseMatrix<double>& matrix) override { solver.initialize(matrix); }
  void solve(const Vector<double>& b, Vector<double>& x) override
  {
    x = b;
    solver.solve(x);
  }
  std::string name() const override { return "umfpack"; }

private:
  SparseDirectUMFPACK solver;
};

/// SuiteSparse KLU (common/klu.h) on a copy of the matrix.
class KluSolver : public EffectiveSolver
{
public:
  void initialize(const SparseMatrix<double>& matrix) override
  {
    const int n = static_cast<int>(matrix.m());
    std::vector<int> entries_per_row(static_cast<std::size_t>(n));
    for (int r = 0; r < n; ++r)
      entries_per_row[static_cast<std::size_t>(r)] =
          static_cast<int>(matrix.get_row_length(static_cast<unsigned int>(r)));
    klu.start_pattern(n, entries_per_row);
    std::vector<int> columns;
    std::vector<double> values;
    for (int r = 0; r < n; ++r)
    {
      columns.clear();
      values.clear();
      for (auto entry = matrix.begin(static_cast<unsigned int>(r));
           entry != matrix.end(static_cast<unsigned int>(r)); ++entry)
      {
        columns.push_back(static_cast<int>(entry->column()));
        values.push_back(entry->value());
      }
      klu.set_row(r, columns, values);
    }
    if (!klu.finish_pattern() || !klu.factorize())
      throw std::runtime_error("KLU could not factorize the effective matrix");
  }
  void solve(const Vector<double>& b, Vector<double>& x) override
  {
    x.reinit(b.size(), true);
    if (!klu.solve(b.begin(), x.begin()))
      throw std::runtime_error("KLU solve failed");
  }
  std::string name() const override { return "klu"; }

private:
  Klu klu;
};

/// SuiteSparse CHOLMOD (Cholesky L L^T, fill-reducing ordering) of the upper triangle: the
/// effective matrix is symmetric positive definite (constrained rows keep a positive diagonal),
/// so one triangular factor serves, about half KLU's work per solve. Simplicial, not
/// supernodal: a time step solves one right-hand side against a factor made once per dt, and
/// the simplicial triangular solves (the supernodal ones run BLAS-2 per supernode) took 2.05
/// against 2.46 ms per step attempt (four solves), the factorizations 2.8 against 5.3 s in
/// all, on the default tunnel's wave alone (8396 Q2 DOFs, about 5300 attempts).
class CholmodSolver : public EffectiveSolver
{
public:
  CholmodSolver()
  {
    cholmod_start(&common);
    common.supernodal = CHOLMOD_SIMPLICIAL;
    common.final_ll = 1; // L L^T: no diagonal pass in the solve
  }
  ~CholmodSolver() override
  {
    for (cholmod_dense** d : {&b_dense, &x_dense, &y_work, &e_work})
      if (*d != nullptr)
        cholmod_free_dense(d, &common);
    if (factor != nullptr)
      cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  void initialize(const SparseMatrix<double>& matrix) override
  {
    const auto n = static_cast<std::size_t>(matrix.m());
    // Column j of the upper triangle = the entries (j, i), i <= j, of row j (symmetric).
    std::vector<std::vector<std::pair<int, double>>> columns(n);
    std::size_t nnz = 0;
    for (std::size_t r = 0; r < n; ++r)
    {
      for (auto e = matrix.begin(static_cast<unsigned int>(r));
           e != matrix.end(static_cast<unsigned int>(r)); ++e)
        if (e->column() <= r && e->value() != 0.0)
          columns[r].emplace_back(static_cast<int>(e->column()), e->value());
      std::sort(columns[r].begin(), columns[r].end());
      nnz += columns[r].size();
    }
    cholmod_sparse* a = cholmod_allocate_sparse(n, n, nnz, 1, 1, 1, CHOLMOD_REAL, &common);
    if (a == nullptr)
      throw std::runtime_error("CHOLMOD could not allocate the effective matrix");
    auto* p = static_cast<int*>(a->p);
    auto* i = static_cast<int*>(a->i);
    auto* x = static_cast<double*>(a->x);
    std::size_t k = 0;
    for (std::size_t c = 0; c < n; ++c)
    {
      p[c] = static_cast<int>(k);
      for (const auto& [row, value] : columns[c])
      {
        i[k] = row;
        x[k++] = value;
      }
    }
    p[n] = static_cast<int>(k);
    factor = cholmod_analyze(a, &common);
    const bool factorized = factor != nullptr && cholmod_factorize(a, factor, &common) != 0 &&
                            common.status == CHOLMOD_OK && factor->minor == n;
    cholmod_free_sparse(&a, &common);
    if (!factorized)
      throw std::runtime_error("CHOLMOD could not factorize the effective matrix (status " +
                               std::to_string(common.status) + "): not positive definite?");
    b_dense = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &common);
  }
  void solve(const Vector<double>& b, Vector<double>& x) override
  {
    std::copy(b.begin(), b.end(), static_cast<double*>(b_dense->x));
    if (cholmod_solve2(CHOLMOD_A, factor, b_dense, nullptr, &x_dense, nullptr, &y_work, &e_work,
                       &common) == 0)
      throw std::runtime_error("CHOLMOD solve failed (status " + std::to_string(common.status) +
                               ")");
    x.reinit(b.size(), true);
    const auto* solution = static_cast<const double*>(x_dense->x);
    std::copy(solution, solution + b.size(), x.begin());
  }
  void solve_columns(const std::vector<Vector<double>>& b, std::vector<Vector<double>>& x) override
  {
    // One call for all columns: the simplicial solve sweeps the factor once per four columns.
    const std::size_t n = factor->n, k = b.size();
    x.resize(k);
    if (k == 0)
      return;
    cholmod_dense* many = cholmod_allocate_dense(n, k, n, CHOLMOD_REAL, &common);
    if (many == nullptr)
      throw std::runtime_error("CHOLMOD could not allocate " + std::to_string(k) + " columns");
    for (std::size_t j = 0; j < k; ++j)
      std::copy(b[j].begin(), b[j].end(), static_cast<double*>(many->x) + j * n);
    cholmod_dense* solution = cholmod_solve(CHOLMOD_A, factor, many, &common);
    cholmod_free_dense(&many, &common);
    if (solution == nullptr)
      throw std::runtime_error("CHOLMOD solve failed (status " + std::to_string(common.status) +
                               ")");
    for (std::size_t j = 0; j < k; ++j)
    {
      x[j].reinit(n, true);
      const auto* column = static_cast<const double*>(solution->x) + j * n;
      std::copy(column, column + n, x[j].begin());
    }
    cholmod_free_dense(&solution, &common);
  }
  std::string name() const override { return "cholmod"; }

private:
  cholmod_common common;
  cholmod_factor* factor = nullptr;
  cholmod_dense* b_dense = nullptr;
  cholmod_dense *x_dense = nullptr, *y_work = nullptr, *e_work = nullptr; ///< reused by solve2
};

/// Conjugate gradients with a Jacobi preconditioner. The effective matrix of a Newmark step is
/// dominated by M / (beta dt^2) at the time steps of wave problems, so it is well conditioned
/// (about 2.2 iterations per decade of residual at dt = 2.4 times the explicit limit). |b| is
/// dominated by M u0 / (beta dt^2), so the default tolerance is 1e-12: the velocity update
/// amplifies the error left in u1 by about 1 / (omega dt) (tests/fem/test_far_field_dynamics.cc
/// measures the agreement with the direct solve). Stopping relative to |A (u1 - u0)| instead
/// cost an extra product and no fewer iterations for the same agreement. SSOR
/// and ILU(0) halve the iterations but each costs about two products, so they were no faster
/// (bench/fem_bench.py).
class CgSolver : public EffectiveSolver
{
public:
  explicit CgSolver(const double tolerance_) : tolerance(tolerance_) {}
  void initialize(const SparseMatrix<double>& matrix_) override
  {
    matrix = &matrix_;
    preconditioner.initialize(matrix_);
  }
  void solve(const Vector<double>& b, Vector<double>& x) override
  {
    const double norm = b.l2_norm();
    if (norm == 0.0)
    {
      x = 0.0;
      iterations = 0;
      return;
    }
    SolverControl control(std::max<unsigned int>(1000, static_cast<unsigned int>(b.size())),
                          tolerance * norm, false, false);
    SolverCG<Vector<double>> cg(control);
    cg.solve(*matrix, x, b, preconditioner);
    iterations = control.last_step();
  }
  unsigned int last_iterations() const override { return iterations; }
  std::string name() const override { return "cg_jacobi"; }

private:
  double tolerance;
  const SparseMatrix<double>* matrix = nullptr;
  PreconditionJacobi<SparseMatrix<double>> preconditioner;
  unsigned int iterations = 0;
};
} // namespace

std::unique_ptr<EffectiveSolver> make_effective_solver(const LinearSolver kind,
                                                       const DirectSolver direct,
                                                       const double relative_tolerance)
{
  if (kind == LinearSolver::cg)
    return std::make_unique<CgSolver>(relative_tolerance);
  if (direct == DirectSolver::umfpack)
    return std::make_unique<UmfpackSolver>();
  if (direct == DirectSolver::cholmod)
    return std::make_unique<CholmodSolver>();
  return std::make_unique<KluSolver>();
}

} // namespace ddafem::fem
