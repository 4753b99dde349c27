// SuiteSparse KLU (sparse LU with BTF and AMD orderings): the one wrapper of the blocks' and the
// far field's KLU solves, with every KLU status checked. SuiteSparse only (no Trilinos), so that
// a blocks-only run does not load deal.II's libraries.
#pragma once

#include <memory>
#include <vector>

namespace ddafem
{
/// A square sparse matrix of fixed pattern, factorized and solved by KLU. Build the pattern
/// with start_pattern, set_row for every row and finish_pattern (which also runs the symbolic
/// factorization); then set_row replaces values, factorize and solve as often as needed.
/// Failures are statuses (false), never exceptions: a failed set_row makes the next
/// finish_pattern or factorize return false.
class Klu
{
public:
  Klu();
  ~Klu();
  Klu(const Klu&) = delete;
  Klu& operator=(const Klu&) = delete;

  /// Starts a matrix of n rows with at most entries_per_row[r] entries in row r.
  void start_pattern(int n, const std::vector<int>& entries_per_row);
  /// Row `row`'s values at `columns`: inserted while the pattern is being built, replacing the
  /// values afterwards (a column not in the pattern then counts as a failure).
  void set_row(int row, const std::vector<int>& columns, const std::vector<double>& values);
  /// Ends the pattern and runs the symbolic factorization; false if any step reported an error.
  bool finish_pattern();
  /// Numeric factorization of the current values; false on an error (e.g. a singular matrix).
  bool factorize();
  /// x = A^-1 b with the last factorization (b and x of n values); false on an error.
  bool solve(const double* b, double* x);

private:
  struct Impl;
  std::unique_ptr<Impl> impl;
};

} // namespace ddafem
