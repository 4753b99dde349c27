#include "common/klu.h"

#include <suitesparse/klu.h>

#include <algorithm>
#include <numeric>

namespace ddafem
{
/// The matrix in compressed rows, handed to KLU as the compressed columns of A^T: the
/// factorization is of A^T, and klu_tsolve solves (A^T)^T x = A x = b.
struct Klu::Impl
{
  Impl() { klu_defaults(&common); }
  ~Impl()
  {
    if (numeric)
      klu_free_numeric(&numeric, &common);
    if (symbolic)
      klu_free_symbolic(&symbolic, &common);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  /// Position of (row, column) in `values`, or -1 if not in the pattern.
  int find(int row, int column) const
  {
    const auto first = columns.begin() + row_start[static_cast<std::size_t>(row)];
    const auto last = columns.begin() + row_start[static_cast<std::size_t>(row) + 1];
    const auto it = std::lower_bound(first, last, column);
    return it != last && *it == column ? static_cast<int>(it - columns.begin()) : -1;
  }

  klu_common common;
  klu_symbolic* symbolic = nullptr;
  klu_numeric* numeric = nullptr;
  int n = 0;
  std::vector<int> capacity;                 ///< per row, while the pattern is built
  std::vector<std::vector<int>> new_columns; ///< per row, while the pattern is built
  std::vector<std::vector<double>> new_values;
  std::vector<int> row_start, columns; ///< the pattern, columns ascending in each row
  std::vector<double> values;
  std::vector<double> work; ///< right-hand side, then solution
  bool pattern_done = false;
  bool failed = false; ///< a set_row reported an error
};

Klu::Klu() : impl(std::make_unique<Impl>()) {}

Klu::~Klu() = default;

void Klu::start_pattern(int n, const std::vector<int>& entries_per_row)
{
  impl = std::make_unique<Impl>();
  impl->n = n;
  impl->capacity = entries_per_row;
  impl->failed = static_cast<int>(entries_per_row.size()) != n;
  impl->new_columns.assign(static_cast<std::size_t>(n), {});
  impl->new_values.assign(static_cast<std::size_t>(n), {});
}

void Klu::set_row(int row, const std::vector<int>& columns, const std::vector<double>& values)
{
  Impl& m = *impl;
  if (row < 0 || row >= m.n || columns.size() != values.size())
  {
    m.failed = true;
    return;
  }
  const auto r = static_cast<std::size_t>(row);
  for (std::size_t k = 0; k < columns.size(); ++k)
  {
    if (columns[k] < 0 || columns[k] >= m.n)
    {
      m.failed = true;
      continue;
    }
    if (!m.pattern_done)
    {
      m.new_columns[r].push_back(columns[k]);
      m.new_values[r].push_back(values[k]);
      continue;
    }
    const int at = m.find(row, columns[k]);
    if (at < 0)
      m.failed = true; // replacing a value outside the pattern
    else
      m.values[static_cast<std::size_t>(at)] = values[k];
  }
  if (!m.pattern_done && static_cast<int>(m.new_columns[r].size()) > m.capacity[r])
    m.failed = true;
}

bool Klu::finish_pattern()
{
  Impl& m = *impl;
  if (m.failed || m.pattern_done)
    return false;
  m.row_start.assign(1, 0);
  for (std::size_t r = 0; r < static_cast<std::size_t>(m.n); ++r)
  {
    // Columns ascending; a column given twice is summed (as Epetra's insertion did).
    std::vector<std::size_t> order(m.new_columns[r].size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b)
                     { return m.new_columns[r][a] < m.new_columns[r][b]; });
    for (const std::size_t k : order)
    {
      const int c = m.new_columns[r][k];
      if (m.columns.size() > static_cast<std::size_t>(m.row_start.back()) && m.columns.back() == c)
        m.values.back() += m.new_values[r][k];
      else
      {
        m.columns.push_back(c);
        m.values.push_back(m.new_values[r][k]);
      }
    }
    m.row_start.push_back(static_cast<int>(m.columns.size()));
  }
  m.new_columns.clear();
  m.new_values.clear();
  m.pattern_done = true;
  m.work.resize(static_cast<std::size_t>(m.n));
  m.symbolic = klu_analyze(m.n, m.row_start.data(), m.columns.data(), &m.common);
  return m.symbolic != nullptr;
}

bool Klu::factorize()
{
  Impl& m = *impl;
  if (!m.symbolic || m.failed)
    return false;
  if (m.numeric)
    klu_free_numeric(&m.numeric, &m.common);
  m.numeric =
      klu_factor(m.row_start.data(), m.columns.data(), m.values.data(), m.symbolic, &m.common);
  // KLU_SINGULAR is a warning with halt_if_singular unset; a singular matrix is a failure here.
  return m.numeric != nullptr && m.common.status == KLU_OK;
}

bool Klu::solve(const double* b, double* x)
{
  Impl& m = *impl;
  if (!m.numeric)
    return false;
  std::copy(b, b + m.n, m.work.begin());
  if (klu_tsolve(m.symbolic, m.numeric, m.n, 1, m.work.data(), &m.common) != 1)
    return false;
  std::copy(m.work.begin(), m.work.end(), x);
  return true;
}

} // namespace ddafem
