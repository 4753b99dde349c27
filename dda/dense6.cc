#include "dda/dense6.h"

#include <cmath>

namespace ddafem::dda
{
bool cholesky_inverse_6(const Matrix6& a, Matrix6& l_inverse)
{
  double l[6][6];             // l[i][j] = L(i, j), i > j
  double inverse_diagonal[6]; // 1 / L(j, j)
#pragma GCC unroll 6
  for (int j = 0; j < 6; ++j)
  {
    double d = a(j, j);
#pragma GCC unroll 6
    for (int p = 0; p < j; ++p)
      d -= l[j][p] * l[j][p];
    if (!(d > 0.0))
      return false;
    inverse_diagonal[j] = std::sqrt(d) * (1.0 / d); // 1 / sqrt(d)
#pragma GCC unroll 6
    for (int i = j + 1; i < 6; ++i)
    {
      double s = a(i, j);
#pragma GCC unroll 6
      for (int p = 0; p < j; ++p)
        s -= l[i][p] * l[j][p];
      l[i][j] = s * inverse_diagonal[j];
    }
  }
  // Column c of X = L^-1: X(c, c) = 1 / L(c, c),
  // X(i, c) = -sum_{c <= p < i} L(i, p) X(p, c) / L(i, i) for i > c.
  double x[6][6] = {}; // x[c][i] = X(i, c)
#pragma GCC unroll 6
  for (int c = 0; c < 6; ++c)
  {
    x[c][c] = inverse_diagonal[c];
#pragma GCC unroll 6
    for (int i = c + 1; i < 6; ++i)
    {
      double s = 0.0;
#pragma GCC unroll 6
      for (int p = c; p < i; ++p)
        s -= l[i][p] * x[c][p];
      x[c][i] = s * inverse_diagonal[i];
    }
  }
  bool finite = true;
#pragma GCC unroll 6
  for (int c = 0; c < 6; ++c)
#pragma GCC unroll 6
    for (int i = 0; i < 6; ++i)
    {
      l_inverse(i, c) = x[c][i];
      finite &= std::isfinite(x[c][i]);
    }
  return finite;
}

bool spd_inverse_6(const Matrix6& a, Matrix6& inverse)
{
  Matrix6 x;
  if (!cholesky_inverse_6(a, x))
    return false;
  // (X^T X)(i, j) = sum over p >= max(i, j) of X(p, i) X(p, j): the upper triangle, mirrored.
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i <= j; ++i)
    {
      double s = 0.0;
      for (int p = j; p < 6; ++p)
        s += x(p, i) * x(p, j);
      inverse(i, j) = s;
      inverse(j, i) = s;
    }
  return inverse.allFinite();
}

} // namespace ddafem::dda
