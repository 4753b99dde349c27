// Far-field meshes with a hole (issue 5): the hole's area and perimeter, grading from the hole to
// the far element size, a wave on the graded mesh, and Gmsh import with named parts.
#include "common/input_error.h"
#include "fem/elastic_wave_model.h"
#include "fem/far_field_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

namespace
{
using namespace ddafem;
using namespace ddafem::fem;

// Rock: rho = 2000 kg/m^3, E = 5 GPa, nu = 0.25: VS = 1000 m/s, VP = 1732 m/s (plane strain).
FarFieldDescription rock(const double width, const double height, const double element_size)
{
  FarFieldDescription d;
  d.lower = {{0.0, 0.0}};
  d.upper = {{width, height}};
  d.element_size = element_size;
  d.degree = 2;
  d.density = 2000.0;
  d.youngs_modulus = 5e9;
  d.poisson_ratio = 0.25;
  return d;
}

/// Longest edge of the elements touching the hole, and of those farther than `far` from it.
struct SizeNearFar
{
  double near = 0.0;
  double far = 0.0;
};

void expect_graded(const ElasticWaveModel& model, const double h_hole, const double far_size)
{
  // Near the hole every element is at most h_hole (the rule of the grading), far away the
  // elements reach the far size (within the factor 2 of bisection) and never exceed it.
  EXPECT_LE(model.smallest_element_size(), h_hole * (1.0 + 1e-9));
  EXPECT_LE(model.element_size(), far_size * (1.0 + 1e-9));
  EXPECT_GT(model.element_size(), 0.5 * far_size);
  EXPECT_GT(model.n_constraints(), 0u); // hanging nodes
}

TEST(FarFieldMesh, RectangularHoleAreaPerimeterAndGrading)
{
  FarFieldDescription d = rock(100.0, 80.0, 8.0);
  d.hole.shape = HoleShape::rectangle;
  d.hole.lower = {{40.0, 30.0}};
  d.hole.upper = {{52.0, 36.0}};
  d.hole.element_size = 0.5;
  d.hole.growth_ratio = 1.3;
  const ElasticWaveModel model(d);
  std::cout << "  " << model.n_cells() << " cells, h " << model.smallest_element_size() << " .. "
            << model.element_size() << " m, " << model.n_dofs() << " dofs\n";
  // The hole's edges are mesh lines: exact up to round-off.
  EXPECT_NEAR(model.area(), 100.0 * 80.0 - 12.0 * 6.0, 1e-9 * 8000.0);
  EXPECT_NEAR(model.boundary_length(BoundaryPart::hole), 2.0 * (12.0 + 6.0), 1e-9 * 36.0);
  EXPECT_NEAR(model.boundary_length(BoundaryPart::bottom), 100.0, 1e-9 * 100.0);
  EXPECT_NEAR(model.boundary_length(BoundaryPart::left), 80.0, 1e-9 * 80.0);
  expect_graded(model, 0.5, 8.0);
}

TEST(FarFieldMesh, PolygonHoleIsExactAndCircleFollowsTheCurve)
{
  // An irregular convex pentagon (clockwise: the mesh orders it itself).
  FarFieldDescription d = rock(60.0, 60.0, 6.0);
  d.hole.shape = HoleShape::polygon;
  d.hole.vertices = {
      {{25.0, 25.0}}, {{24.0, 32.0}}, {{31.0, 36.0}}, {{36.0, 30.0}}, {{33.0, 24.0}}};
  d.hole.element_size = 0.75;
  double twice_area = 0.0, perimeter = 0.0;
  for (std::size_t i = 0; i < 5; ++i)
  {
    const auto& a = d.hole.vertices[i];
    const auto& b = d.hole.vertices[(i + 1) % 5];
    twice_area += a[0] * b[1] - a[1] * b[0];
    perimeter += std::hypot(b[0] - a[0], b[1] - a[1]);
  }
  const ElasticWaveModel polygon(d);
  EXPECT_NEAR(polygon.area(), 3600.0 - 0.5 * std::abs(twice_area), 1e-9 * 3600.0);
  EXPECT_NEAR(polygon.boundary_length(BoundaryPart::hole), perimeter, 1e-9 * perimeter);
  expect_graded(polygon, 0.75, 6.0);

  // A circle of radius 5 m: the boundary vertices lie on the circle, so the area and the
  // perimeter of the inscribed polygon of edges <= 0.5 m differ from pi r^2 and 2 pi r by at
  // most (pi / n)^2 / 6 with n >= 2 pi r / 0.5 = 63 edges: 4e-4.
  d.hole.shape = HoleShape::circle;
  d.hole.center = {{30.0, 30.0}};
  d.hole.radius = 5.0;
  d.hole.element_size = 0.5;
  const ElasticWaveModel circle(d);
  std::cout << "  circle: " << circle.n_cells() << " cells, hole perimeter "
            << circle.boundary_length(BoundaryPart::hole) << " m (2 pi r = " << 10.0 * M_PI
            << ")\n";
  EXPECT_NEAR(circle.area(), 3600.0 - M_PI * 25.0, 5e-4 * M_PI * 25.0);
  EXPECT_NEAR(circle.boundary_length(BoundaryPart::hole), 10.0 * M_PI, 5e-4 * 10.0 * M_PI);
  expect_graded(circle, 0.5, 6.0);
}

TEST(FarFieldMesh, RejectsHolesThatDoNotFit)
{
  FarFieldDescription d = rock(20.0, 20.0, 2.0);
  d.hole.shape = HoleShape::circle;
  d.hole.center = {{18.0, 10.0}};
  d.hole.radius = 3.0; // reaches x = 21 > 20
  EXPECT_THROW(ElasticWaveModel{d}, InputError);
  d.hole.center = {{10.0, 10.0}};
  d.hole.growth_ratio = 1.0;
  EXPECT_THROW(ElasticWaveModel{d}, InputError);
  d.hole.growth_ratio = 1.3;
  d.hole.shape = HoleShape::polygon; // an arrow head: not star-shaped about its centroid
  d.hole.vertices = {{{5.0, 5.0}}, {{15.0, 10.0}}, {{5.0, 15.0}}, {{14.0, 10.0}}};
  EXPECT_THROW(ElasticWaveModel{d}, InputError);
  d.hole.shape = HoleShape::none;
  d.boundaries = {{BoundaryPart::hole, BoundaryKind::fixed, 1.0, 1.0, {}}};
  EXPECT_THROW(ElasticWaveModel{d}, InputError); // a `hole` part without a hole
  d.boundaries.clear();
  d.hole.shape = HoleShape::circle;
  d.monitors = {{"in the hole", {{10.0, 10.0}}}};
  try
  {
    const ElasticWaveModel model(d);
    ADD_FAILURE() << "a monitor in the hole was accepted";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("in the hole"), std::string::npos) << e.what();
  }
}

// The 1D P column of test_elastic_wave_model.cc (16 m x 200 m, Q2 of 4 m, one-cycle 25 Hz sine
// of 0.1 m/s through the Joyner-Chen base, rollers) with a 2 m x 2 m hole at 170 m graded down
// to 0.5 m elements: below the hole, before anything scattered by it comes back, the column is
// still one-dimensional. The hanging-node constraints must keep the trapezoidal rule's exact
// energy balance.
TEST(FarFieldMesh, PColumnWithAGradedHoleStillCarriesThePlaneWave)
{
  FarFieldDescription d = rock(16.0, 200.0, 4.0);
  d.hole.shape = HoleShape::rectangle;
  d.hole.lower = {{7.0, 170.0}};
  d.hole.upper = {{9.0, 172.0}};
  d.hole.element_size = 0.5;
  d.boundaries = {{BoundaryPart::bottom, BoundaryKind::input, 1.0, 1.0, {}},
                  {BoundaryPart::top, BoundaryKind::lysmer, 1.0, 1.0, {}},
                  {BoundaryPart::left, BoundaryKind::roller, 1.0, 1.0, {}},
                  {BoundaryPart::right, BoundaryKind::roller, 1.0, 1.0, {}}};
  d.incident.type = IncidentWave::Type::p;
  d.incident.velocity = TimeFunction::sine_pulse(0.1, 25.0, 1.0, 0.0);
  d.monitors = {{"low", {{8.0, 50.0}}}, {"mid", {{8.0, 100.0}}}};
  const double dt = 4e-4;
  d.dt = dt;
  ElasticWaveModel model(d);
  EXPECT_LE(model.smallest_element_size(), 0.5 + 1e-12);
  const double vp = model.p_wave_speed();
  // Stop when the pulse (0.04 s long) has passed the mid monitor (100 m), before waves
  // scattered back by the hole (at 170 m) arrive there at (170 + 70) / VP.
  const double end_time = 100.0 / vp + 1.5 / 25.0;
  std::vector<double> low, mid, time;
  while (model.time() < end_time)
  {
    ASSERT_TRUE(model.advance(dt).taken);
    time.push_back(model.time());
    low.push_back(model.sample_monitor(0).velocity[1]);
    mid.push_back(model.sample_monitor(1).velocity[1]);
  }
  const auto peak = [&](const std::vector<double>& v)
  {
    const auto i = static_cast<std::size_t>(std::max_element(v.begin(), v.end()) - v.begin());
    const double denominator = v[i - 1] - 2.0 * v[i] + v[i + 1];
    return std::make_pair(time[i] + 0.5 * (v[i - 1] - v[i + 1]) / denominator * dt, v[i]);
  };
  const auto [t_low, v_low] = peak(low);
  const auto [t_mid, v_mid] = peak(mid);
  const double speed = 50.0 / (t_mid - t_low);
  std::cout << "  graded column: " << model.n_dofs() << " dofs, speed " << speed << " m/s (VP "
            << vp << "), peaks " << v_low << ", " << v_mid << " m/s\n";
  // The same bounds as the column without a hole: speed within 1%, amplitude within 2%.
  EXPECT_NEAR(speed, vp, 0.01 * vp);
  EXPECT_NEAR(v_low, 0.1, 0.002);
  EXPECT_NEAR(v_mid, 0.1, 0.002);
  const EnergyBalance e = model.energy();
  EXPECT_NEAR(e.dissipated, 0.0, 1e-9 * e.work_of_input);
}

TEST(FarFieldMesh, GmshFileWithNamedParts)
{
  // The same plate as msh 2.2 and 4.1 (tests/fem/data/make_plate_msh.py).
  FarFieldDescription d = rock(1.0, 1.0, 0.0);
  for (const char* name : {"plate_with_hole_v4.msh", "plate_with_hole.msh"})
  {
    d.mesh_file.file = std::string(DDAFEM_SOURCE_DIR) + "/tests/fem/data/" + name;
    d.mesh_file.parts = {{BoundaryPart::bottom, 1},
                         {BoundaryPart::right, 2},
                         {BoundaryPart::top, 3},
                         {BoundaryPart::hole, 5}}; // tag 4 (left) stays free
    d.boundaries = {{BoundaryPart::bottom, BoundaryKind::fixed, 1.0, 1.0, {}},
                    {BoundaryPart::hole, BoundaryKind::lysmer, 1.0, 1.0, {}}};
    d.monitors = {{"corner", {{5.5, 3.5}}}};
    const ElasticWaveModel model(d);
    EXPECT_EQ(model.n_cells(), 20u);
    EXPECT_NEAR(model.area(), 20.0, 1e-12);
    EXPECT_NEAR(model.boundary_length(BoundaryPart::hole), 8.0, 1e-12);
    EXPECT_NEAR(model.boundary_length(BoundaryPart::bottom), 6.0, 1e-12);
    EXPECT_NEAR(model.boundary_length(BoundaryPart::right), 4.0, 1e-12);
    EXPECT_NEAR(model.boundary_length(BoundaryPart::left), 0.0, 1e-12);
    EXPECT_NEAR(model.element_size(), 1.0, 1e-12);
    // Fixed bottom: 7 nodes of Q2 on each of 6 edges -> 13 nodes x 2 components.
    EXPECT_EQ(model.n_constraints(), 26u);
  }

  FarFieldDescription unknown = d;
  unknown.mesh_file.parts[BoundaryPart::hole] = 7;
  try
  {
    const ElasticWaveModel bad(unknown);
    ADD_FAILURE() << "an unknown tag was accepted";
  }
  catch (const InputError& e)
  {
    const std::string message = e.what();
    EXPECT_NE(message.find("mesh.parts.hole = 7"), std::string::npos) << message;
    EXPECT_NE(message.find("1, 2, 3, 4, 5"), std::string::npos) << message;
  }
  FarFieldDescription missing = d;
  missing.mesh_file.file += ".absent";
  EXPECT_THROW(ElasticWaveModel{missing}, InputError);
}

} // namespace
