#include "common/amesos_klu.h"

#include <Amesos_Klu.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_Map.h>
#include <Epetra_MultiVector.h>
#include <Epetra_SerialComm.h>

#include <algorithm>

namespace ddafem
{
struct AmesosKlu::Impl
{
  Epetra_SerialComm comm;
  std::unique_ptr<Epetra_Map> map;
  std::unique_ptr<Epetra_CrsMatrix> matrix;
  std::unique_ptr<Epetra_MultiVector> x_vec, b_vec;
  std::unique_ptr<Epetra_LinearProblem> problem;
  std::unique_ptr<Amesos_Klu> klu;
  int n = 0;
  bool pattern_done = false;
  bool failed = false; ///< a set_row reported an error
};

AmesosKlu::AmesosKlu() : impl(std::make_unique<Impl>()) {}

AmesosKlu::~AmesosKlu() = default;

void AmesosKlu::start_pattern(int n, const std::vector<int>& entries_per_row)
{
  impl = std::make_unique<Impl>();
  impl->n = n;
  impl->map = std::make_unique<Epetra_Map>(n, 0, impl->comm);
  impl->matrix = std::make_unique<Epetra_CrsMatrix>(Copy, *impl->map, entries_per_row.data(), true);
}

void AmesosKlu::set_row(int row, const std::vector<int>& columns, const std::vector<double>& values)
{
  // Epetra: 0 success, < 0 an error, > 0 a warning: benign while inserting (storage grown),
  // a value ignored when replacing (its column is not in the pattern).
  const int code = impl->pattern_done
                       ? impl->matrix->ReplaceGlobalValues(row, static_cast<int>(columns.size()),
                                                           values.data(), columns.data())
                       : impl->matrix->InsertGlobalValues(row, static_cast<int>(columns.size()),
                                                          values.data(), columns.data());
  impl->failed = impl->failed || code < 0 || (impl->pattern_done && code > 0);
}

bool AmesosKlu::finish_pattern()
{
  if (impl->failed || impl->matrix->FillComplete() != 0)
    return false;
  impl->pattern_done = true;
  impl->x_vec = std::make_unique<Epetra_MultiVector>(*impl->map, 1);
  impl->b_vec = std::make_unique<Epetra_MultiVector>(*impl->map, 1);
  impl->problem = std::make_unique<Epetra_LinearProblem>(impl->matrix.get(), impl->x_vec.get(),
                                                         impl->b_vec.get());
  impl->klu = std::make_unique<Amesos_Klu>(*impl->problem);
  return impl->klu->SymbolicFactorization() == 0;
}

bool AmesosKlu::factorize()
{
  return impl->klu && !impl->failed && impl->klu->NumericFactorization() == 0;
}

bool AmesosKlu::solve(const double* b, double* x)
{
  if (!impl->klu)
    return false;
  std::copy(b, b + impl->n, (*impl->b_vec)[0]);
  if (impl->klu->Solve() != 0)
    return false;
  std::copy((*impl->x_vec)[0], (*impl->x_vec)[0] + impl->n, x);
  return true;
}

} // namespace ddafem
