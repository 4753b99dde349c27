// DDA submatrices: rigid-body modes, mass matrix in closed form and by quadrature.
#include "dda/submatrices.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

using namespace ddafem::dda;

TEST(Submatrices, RigidBodyModesProduceNoStrain)
{
  // A rigid motion (translation + small rotation) leaves the strain unknowns zero, so the
  // elastic energy d^T K d / 2 vanishes, and T d is the rigid displacement field.
  const std::vector<Point> poly = {{0, 0}, {3, 0}, {3.5, 2}, {1, 2.5}, {-0.5, 1}};
  const PolygonMoments m = polygon_moments(poly);
  const Matrix6 k = elastic_stiffness(m.area, elasticity_matrix(50e9, 0.25, PlaneMode::stress));
  Vector6 d;
  d << 1e-3, -2e-3, 1e-4, 0, 0, 0;
  EXPECT_DOUBLE_EQ(d.dot(k * d), 0.0);
  for (const Point& x : poly)
  {
    const Vector2 u = displacement_matrix(m.centroid, x) * d;
    const Vector2 r = x - m.centroid;
    EXPECT_NEAR(u.x(), 1e-3 - 1e-4 * r.y(), 1e-15);
    EXPECT_NEAR(u.y(), -2e-3 + 1e-4 * r.x(), 1e-15);
  }
}

TEST(Submatrices, StrainModesGiveUniformStrain)
{
  // d = (0,0,0, ex, ey, g): u = (ex dx + g dy / 2, ey dy + g dx / 2), a symmetric strain.
  const Point c(1, 1);
  Vector6 d;
  d << 0, 0, 0, 1e-4, -2e-4, 3e-4;
  const Vector2 u = displacement_matrix(c, Point(2, 3)) * d;
  EXPECT_NEAR(u.x(), 1e-4 * 1 + 1.5e-4 * 2, 1e-18);
  EXPECT_NEAR(u.y(), -2e-4 * 2 + 1.5e-4 * 1, 1e-18);
}

TEST(Submatrices, DisplacementAtEqualsTTimesDBitForBit)
{
  // The step control compares the largest vertex displacement against g2 w0 and sets dt from
  // it: the shortcut must give the product's bits, at every scale from 1e-20 to 1e5.
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), exponent(-20.0, 5.0);
  const auto value = [&] { return unit(random) * std::pow(10.0, exponent(random)); };
  for (int n = 0; n < 200000; ++n)
  {
    const Point c(100.0 * unit(random), 100.0 * unit(random));
    const Point x(c.x() + value(), c.y() + value());
    Vector6 d;
    for (int k = 0; k < 6; ++k)
      d[k] = value();
    const Vector2 product = displacement_matrix(c, x) * d;
    const Vector2 shortcut = displacement_at(c, x, d);
    ASSERT_EQ(std::memcmp(product.data(), shortcut.data(), sizeof(Vector2)), 0)
        << "c = " << c.transpose() << ", x = " << x.transpose() << ", d = " << d.transpose();
  }
}

TEST(Submatrices, RectangleMassMatrixClosedForm)
{
  // w x h rectangle: M = rho diag-like with M22 = Sxx + Syy, M25 = (Sxx - Syy) / 2,
  // M55 = (Sxx + Syy) / 4, M33 = Sxx, M44 = Syy, where Sxx = w^3 h / 12, Syy = w h^3 / 12.
  const double w = 2.0, h = 1.0, rho = 2650.0;
  const PolygonMoments m = polygon_moments({{0, 0}, {w, 0}, {w, h}, {0, h}});
  const Matrix6 mass = mass_matrix(m, rho);
  const double sxx = w * w * w * h / 12, syy = w * h * h * h / 12;
  Matrix6 expected = Matrix6::Zero();
  expected(0, 0) = expected(1, 1) = w * h;
  expected(2, 2) = sxx + syy;
  expected(2, 5) = expected(5, 2) = (sxx - syy) / 2;
  expected(5, 5) = (sxx + syy) / 4;
  expected(3, 3) = sxx;
  expected(4, 4) = syy;
  expected *= rho;
  EXPECT_LT((mass - expected).norm(), 1e-9 * expected.norm());
}

TEST(Submatrices, MassMatrixOfConcavePolygonByQuadrature)
{
  // L-shape split into three unit squares; integrate rho T^T T with 3x3 Gauss points on each.
  const std::vector<Point> l = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const PolygonMoments m = polygon_moments(l);
  const double rho = 1000.0;
  const double g[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double wg[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  Matrix6 quad = Matrix6::Zero();
  for (const Point& corner : {Point(0, 0), Point(1, 0), Point(0, 1)})
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
      {
        const Point x = corner + Point(0.5 + 0.5 * g[i], 0.5 + 0.5 * g[j]);
        const Matrix26 t = displacement_matrix(m.centroid, x);
        quad += rho * 0.25 * wg[i] * wg[j] * t.transpose() * t;
      }
  EXPECT_LT((mass_matrix(m, rho) - quad).norm(), 1e-10 * quad.norm());
}

TEST(Submatrices, ElasticityMatrices)
{
  const double e = 50e9, nu = 0.25;
  const auto ps = elasticity_matrix(e, nu, PlaneMode::stress);
  // Uniaxial stress: sigma = (s, 0, 0) needs strain (s/E, -nu s/E, 0).
  const Voigt eps(1.0 / e, -nu / e, 0.0);
  const Voigt s = ps * eps;
  EXPECT_NEAR(s[0], 1.0, 1e-12);
  EXPECT_NEAR(s[1], 0.0, 1e-12);
  const auto pe = elasticity_matrix(e, nu, PlaneMode::strain);
  // Plane strain P modulus: E (1-nu) / ((1+nu)(1-2nu)) = 1.2 E for nu = 0.25.
  EXPECT_NEAR(pe(0, 0), 1.2 * e, 1e-3);
  // Shear modulus G = E / (2 (1 + nu)) in both.
  EXPECT_NEAR(ps(2, 2), e / 2.5, 1e-3);
  EXPECT_NEAR(pe(2, 2), e / 2.5, 1e-3);
}
