// Far-field meshes (issue 5): the rectangle, the rectangle with a graded hole, Gmsh files.
#include "fem/far_field_mesh.h"

#include "fem/far_field_kernels.h"

#include "common/format.h"
#include "common/input_error.h"

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace ddafem::fem
{
using namespace dealii;

namespace
{
using Vertex = std::array<double, 2>;

void require(const bool condition, const std::string& message)
{
  if (!condition)
    throw InputError("far field: " + message);
}

double cross(const Vertex& a, const Vertex& b)
{
  return a[0] * b[1] - a[1] * b[0];
}

Vertex minus(const Vertex& a, const Vertex& b)
{
  return {{a[0] - b[0], a[1] - b[1]}};
}

double norm(const Vertex& a)
{
  return std::hypot(a[0], a[1]);
}

/// Vertices of a rectangle or polygon hole, counterclockwise.
std::vector<Vertex> hole_polygon(const HoleDescription& hole)
{
  if (hole.shape == HoleShape::rectangle)
    return {{{hole.lower[0], hole.lower[1]}},
            {{hole.upper[0], hole.lower[1]}},
            {{hole.upper[0], hole.upper[1]}},
            {{hole.lower[0], hole.upper[1]}}};
  std::vector<Vertex> v = hole.vertices;
  double twice_area = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i)
    twice_area += cross(v[i], v[(i + 1) % v.size()]);
  if (twice_area < 0.0)
    std::reverse(v.begin(), v.end());
  return v;
}

/// Area centroid of a counterclockwise polygon.
Vertex centroid(const std::vector<Vertex>& v)
{
  double twice_area = 0.0, cx = 0.0, cy = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i)
  {
    const Vertex& a = v[i];
    const Vertex& b = v[(i + 1) % v.size()];
    const double w = cross(a, b);
    twice_area += w;
    cx += (a[0] + b[0]) * w;
    cy += (a[1] + b[1]) * w;
  }
  return {{cx / (3.0 * twice_area), cy / (3.0 * twice_area)}};
}

double distance_to_segment(const Vertex& p, const Vertex& a, const Vertex& b)
{
  const Vertex ab = minus(b, a), ap = minus(p, a);
  const double length2 = ab[0] * ab[0] + ab[1] * ab[1];
  const double s =
      length2 > 0.0 ? std::clamp((ap[0] * ab[0] + ap[1] * ab[1]) / length2, 0.0, 1.0) : 0.0;
  return std::hypot(ap[0] - s * ab[0], ap[1] - s * ab[1]);
}

bool inside_polygon(const Vertex& p, const std::vector<Vertex>& v)
{
  bool inside = false;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++)
    if ((v[i][1] > p[1]) != (v[j][1] > p[1]) &&
        p[0] < (v[j][0] - v[i][0]) * (p[1] - v[i][1]) / (v[j][1] - v[i][1]) + v[i][0])
      inside = !inside;
  return inside;
}

/// Where the ray from `c` through `through` leaves the (star-shaped) hole.
Vertex ray_to_hole(const HoleDescription& hole, const std::vector<Vertex>& polygon, const Vertex& c,
                   const Vertex& through)
{
  const Vertex d = minus(through, c);
  if (hole.shape == HoleShape::circle)
  {
    const double scale = hole.radius / norm(d);
    return {{c[0] + scale * d[0], c[1] + scale * d[1]}};
  }
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const Vertex& a = polygon[i];
    const Vertex e = minus(polygon[(i + 1) % polygon.size()], a);
    const double denominator = cross(d, e);
    if (denominator == 0.0)
      continue;
    const Vertex ca = minus(a, c);
    const double t = cross(ca, e) / denominator;
    const double s = cross(ca, d) / denominator;
    if (t > 0.0 && s >= -1e-12 && s <= 1.0 + 1e-12)
      best = std::min(best, t);
  }
  return {{c[0] + best * d[0], c[1] + best * d[1]}};
}

double wrapped_angle_difference(const double a, const double b)
{
  double d = std::fmod(std::abs(a - b), 2.0 * M_PI);
  return std::min(d, 2.0 * M_PI - d);
}

/// `n` equal intervals from a to b (n + 1 values, the last exactly b).
std::vector<double> subdivide(const double a, const double b, const unsigned int n)
{
  std::vector<double> x(n + 1);
  for (unsigned int i = 0; i <= n; ++i)
    x[i] = a + (b - a) * i / n;
  x[n] = b;
  return x;
}

void check_hole(const FarFieldDescription& d)
{
  const HoleDescription& hole = d.hole;
  require(hole.element_size >= 0.0,
          "hole.element_size = " + format_number(hole.element_size) + ", expected >= 0");
  require(hole.growth_ratio > 1.0,
          "hole.growth_ratio = " + format_number(hole.growth_ratio) + ", expected > 1");
  double x0 = 0.0, x1 = 0.0, y0 = 0.0, y1 = 0.0;
  if (hole.shape == HoleShape::circle)
  {
    require(hole.radius > 0.0, "hole.radius = " + format_number(hole.radius) + ", expected > 0");
    x0 = hole.center[0] - hole.radius;
    x1 = hole.center[0] + hole.radius;
    y0 = hole.center[1] - hole.radius;
    y1 = hole.center[1] + hole.radius;
  }
  else
  {
    if (hole.shape == HoleShape::rectangle)
      require(hole.upper[0] > hole.lower[0] && hole.upper[1] > hole.lower[1],
              "hole.upper = (" + format_number(hole.upper[0]) + ", " +
                  format_number(hole.upper[1]) + "), expected above and right of hole.lower (" +
                  format_number(hole.lower[0]) + ", " + format_number(hole.lower[1]) + ")");
    else
      require(hole.vertices.size() >= 3, "hole.vertices has " +
                                             std::to_string(hole.vertices.size()) +
                                             " points, expected at least 3");
    const std::vector<Vertex> polygon = hole_polygon(hole);
    double twice_area = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i)
      twice_area += cross(polygon[i], polygon[(i + 1) % polygon.size()]);
    require(twice_area > 0.0, "hole.vertices enclose no area, expected a simple polygon");
    const Vertex c = centroid(polygon);
    for (std::size_t i = 0; i < polygon.size(); ++i)
      require(cross(minus(polygon[i], c), minus(polygon[(i + 1) % polygon.size()], c)) > 0.0,
              "hole.vertices: the polygon is not star-shaped about its centroid (" +
                  format_number(c[0]) + ", " + format_number(c[1]) +
                  "), expected a polygon every vertex of which is seen from "
                  "the centroid (e.g. a convex one)");
    x0 = x1 = polygon[0][0];
    y0 = y1 = polygon[0][1];
    for (const Vertex& p : polygon)
    {
      x0 = std::min(x0, p[0]);
      x1 = std::max(x1, p[0]);
      y0 = std::min(y0, p[1]);
      y1 = std::max(y1, p[1]);
    }
  }
  require(x0 > d.lower[0] && x1 < d.upper[0] && y0 > d.lower[1] && y1 < d.upper[1],
          "the hole spans [" + format_number(x0) + ", " + format_number(x1) + "] x [" +
              format_number(y0) + ", " + format_number(y1) +
              "], expected it strictly inside the far field [" + format_number(d.lower[0]) + ", " +
              format_number(d.upper[0]) + "] x [" + format_number(d.lower[1]) + ", " +
              format_number(d.upper[1]) + "]");
}

/// Boundary ids of a generated mesh from face positions: the rectangle's sides, else the hole.
void set_boundary_ids(const FarFieldDescription& d, Triangulation<2>& mesh, const bool circle)
{
  const double tol = 1e-9 * std::hypot(d.upper[0] - d.lower[0], d.upper[1] - d.lower[1]);
  for (const auto& cell : mesh.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
    {
      if (!cell->face(f)->at_boundary())
        continue;
      const Point<2> p = cell->face(f)->center();
      BoundaryPart part = BoundaryPart::hole;
      if (std::abs(p[0] - d.lower[0]) < tol)
        part = BoundaryPart::left;
      else if (std::abs(p[0] - d.upper[0]) < tol)
        part = BoundaryPart::right;
      else if (std::abs(p[1] - d.lower[1]) < tol)
        part = BoundaryPart::bottom;
      else if (std::abs(p[1] - d.upper[1]) < tol)
        part = BoundaryPart::top;
      cell->face(f)->set_boundary_id(boundary_id_of(part));
      if (part == BoundaryPart::hole && circle)
        cell->face(f)->set_manifold_id(1);
    }
}

/// The box around the hole that the O-grid fills, and its nodes: the box's corners x0 < x1,
/// y0 < y1 [m], nx by ny intervals, `box` its nodes counterclockwise from the lower-left corner
/// and `inner` the hole point of each node's ray from the centre.
struct HoleRing
{
  double x0 = 0.0, x1 = 0.0, y0 = 0.0, y1 = 0.0;
  unsigned int nx = 0, ny = 0;
  std::vector<double> xs, ys; ///< node coordinates along the box's sides
  std::vector<Vertex> box, inner;
};

/// The hole's bounding box widened on every side by half its larger dimension (so that the
/// ring is about equally thick all round), clipped to the rectangle.
void set_ring_box(const FarFieldDescription& d, const std::vector<Vertex>& polygon, const Vertex& c,
                  HoleRing& ring)
{
  const HoleDescription& hole = d.hole;
  double hx0 = c[0] - hole.radius, hx1 = c[0] + hole.radius;
  double hy0 = c[1] - hole.radius, hy1 = c[1] + hole.radius;
  if (hole.shape != HoleShape::circle)
  {
    hx0 = hx1 = polygon[0][0];
    hy0 = hy1 = polygon[0][1];
    for (const Vertex& p : polygon)
    {
      hx0 = std::min(hx0, p[0]);
      hx1 = std::max(hx1, p[0]);
      hy0 = std::min(hy0, p[1]);
      hy1 = std::max(hy1, p[1]);
    }
  }
  const double margin = 0.5 * std::max(hx1 - hx0, hy1 - hy0);
  ring.x0 = std::max(d.lower[0], hx0 - margin);
  ring.x1 = std::min(d.upper[0], hx1 + margin);
  ring.y0 = std::max(d.lower[1], hy0 - margin);
  ring.y1 = std::min(d.upper[1], hy1 + margin);
}

/// The box's nodes for ring.nx, ring.ny intervals and the hole points of their rays.
void set_ring_nodes(const HoleDescription& hole, const std::vector<Vertex>& polygon,
                    const Vertex& c, HoleRing& ring)
{
  const unsigned int nx = ring.nx, ny = ring.ny;
  ring.xs = subdivide(ring.x0, ring.x1, nx);
  ring.ys = subdivide(ring.y0, ring.y1, ny);
  ring.box.clear();
  for (unsigned int i = 0; i < nx; ++i)
    ring.box.push_back({{ring.xs[i], ring.y0}});
  for (unsigned int i = 0; i < ny; ++i)
    ring.box.push_back({{ring.x1, ring.ys[i]}});
  for (unsigned int i = 0; i < nx; ++i)
    ring.box.push_back({{ring.xs[nx - i], ring.y1}});
  for (unsigned int i = 0; i < ny; ++i)
    ring.box.push_back({{ring.x0, ring.ys[ny - i]}});
  ring.inner.clear();
  for (const Vertex& b : ring.box)
    ring.inner.push_back(ray_to_hole(hole, polygon, c, b));
}

/// Moves each polygon vertex onto the hole point of its nearest ray (in angle about c); false
/// if two vertices share a ray.
bool snap_vertices_to_rays(const std::vector<Vertex>& polygon, const Vertex& c, HoleRing& ring)
{
  std::vector<int> owner(ring.box.size(), -1);
  bool distinct = true;
  for (std::size_t m = 0; m < polygon.size() && distinct; ++m)
  {
    const double phi = std::atan2(polygon[m][1] - c[1], polygon[m][0] - c[0]);
    std::size_t nearest = 0;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < ring.box.size(); ++j)
    {
      const double diff =
          wrapped_angle_difference(phi, std::atan2(ring.box[j][1] - c[1], ring.box[j][0] - c[0]));
      if (diff < best)
      {
        best = diff;
        nearest = j;
      }
    }
    distinct = owner[nearest] < 0;
    owner[nearest] = static_cast<int>(m);
    ring.inner[nearest] = polygon[m];
  }
  return distinct;
}

/// Rays from c through the box nodes, counterclockwise from the box's lower-left corner; each
/// polygon vertex is moved onto the hole point of its nearest ray (more rays until all
/// vertices have rays of their own).
HoleRing make_ring(const FarFieldDescription& d, const double far_size,
                   const std::vector<Vertex>& polygon, const Vertex& c)
{
  HoleRing ring;
  set_ring_box(d, polygon, c, ring);
  const unsigned int n_min = d.hole.shape == HoleShape::circle ? 4 : 2;
  ring.nx = std::max(n_min, element_intervals(ring.x1 - ring.x0, far_size));
  ring.ny = std::max(n_min, element_intervals(ring.y1 - ring.y0, far_size));
  for (unsigned int attempt = 0;; ++attempt)
  {
    set_ring_nodes(d.hole, polygon, c, ring);
    if (snap_vertices_to_rays(polygon, c, ring))
      return ring;
    require(attempt < 8, "hole.vertices: " + std::to_string(polygon.size()) +
                             " vertices too close together in angle about the centroid to mesh, "
                             "expected fewer or more evenly spread vertices");
    ring.nx *= 2;
    ring.ny *= 2;
  }
}

/// Quadrilaterals for Triangulation::create_triangulation; equal points share a vertex.
class CellList
{
public:
  void add_cell(const Vertex& a, const Vertex& b, const Vertex& e, const Vertex& f)
  {
    CellData<2> cell;
    cell.vertices = {vertex(a), vertex(b), vertex(e), vertex(f)};
    cells.push_back(cell);
  }
  std::vector<Point<2>> vertices;
  std::vector<CellData<2>> cells;

private:
  unsigned int vertex(const Vertex& p)
  {
    const auto [it, inserted] = index.emplace(std::make_pair(p[0], p[1]), vertices.size());
    if (inserted)
      vertices.emplace_back(p[0], p[1]);
    return it->second;
  }
  std::map<std::pair<double, double>, unsigned int> index;
};

/// The O-grid between the hole and the box. Layers: geometric radii as in a log-polar grid, so
/// that ring elements are roughly square.
void add_ring_cells(const HoleRing& ring, CellList& cells)
{
  const std::size_t n_rays = ring.box.size();
  double hole_perimeter = 0.0;
  for (std::size_t j = 0; j < n_rays; ++j)
    hole_perimeter += norm(minus(ring.inner[(j + 1) % n_rays], ring.inner[j]));
  const double box_perimeter = 2.0 * ((ring.x1 - ring.x0) + (ring.y1 - ring.y0));
  const double r1 = hole_perimeter / (2.0 * M_PI), r2 = box_perimeter / (2.0 * M_PI);
  const auto n_layers = static_cast<unsigned int>(
      std::max(1L, std::lround(n_rays / (2.0 * M_PI) * std::log(std::max(r2 / r1, 1.0 + 1e-12)))));
  const auto ring_point = [&](const std::size_t j, const unsigned int k) -> Vertex
  {
    if (k == n_layers)
      return ring.box[j % n_rays];
    const double s = r2 > r1 ? (r1 * std::pow(r2 / r1, double(k) / n_layers) - r1) / (r2 - r1)
                             : double(k) / n_layers;
    const Vertex& q = ring.inner[j % n_rays];
    const Vertex& b = ring.box[j % n_rays];
    return {{q[0] + s * (b[0] - q[0]), q[1] + s * (b[1] - q[1])}};
  };
  // x runs outward, y counterclockwise (positive Jacobian).
  for (std::size_t j = 0; j < n_rays; ++j)
    for (unsigned int k = 0; k < n_layers; ++k)
      cells.add_cell(ring_point(j, k), ring_point(j, k + 1), ring_point(j + 1, k),
                     ring_point(j + 1, k + 1));
}

/// Grid lines along one axis: far-size bands from lo to the box side b0 and from b1 to hi
/// around the box's own nodes `inside` (reused bit for bit); `offset` = index of inside[0].
std::vector<double> grid_axis(const double lo, const double b0, const std::vector<double>& inside,
                              const double b1, const double hi, const double far_size,
                              unsigned int& offset)
{
  std::vector<double> x;
  if (b0 > lo)
  {
    const std::vector<double> band = subdivide(lo, b0, element_intervals(b0 - lo, far_size));
    x.insert(x.end(), band.begin(), band.end() - 1);
  }
  offset = static_cast<unsigned int>(x.size());
  x.insert(x.end(), inside.begin(), inside.end());
  if (hi > b1)
  {
    const std::vector<double> band = subdivide(b1, hi, element_intervals(hi - b1, far_size));
    x.insert(x.end(), band.begin() + 1, band.end());
  }
  return x;
}

/// Cartesian cells outside the box.
void add_outer_cells(const FarFieldDescription& d, const HoleRing& ring, const double far_size,
                     CellList& cells)
{
  unsigned int ix = 0, iy = 0;
  const std::vector<double> X =
      grid_axis(d.lower[0], ring.x0, ring.xs, ring.x1, d.upper[0], far_size, ix);
  const std::vector<double> Y =
      grid_axis(d.lower[1], ring.y0, ring.ys, ring.y1, d.upper[1], far_size, iy);
  for (std::size_t j = 0; j + 1 < Y.size(); ++j)
    for (std::size_t i = 0; i + 1 < X.size(); ++i)
    {
      if (i >= ix && i < ix + ring.nx && j >= iy && j < iy + ring.ny)
        continue;
      cells.add_cell({{X[i], Y[j]}}, {{X[i + 1], Y[j]}}, {{X[i], Y[j + 1]}},
                     {{X[i + 1], Y[j + 1]}});
    }
}

/// The coarse mesh around a hole: O-grid between the hole and a box, Cartesian grid outside.
void make_coarse_hole_mesh(const FarFieldDescription& d, const double far_size,
                           Triangulation<2>& mesh)
{
  const HoleDescription& hole = d.hole;
  const bool circle = hole.shape == HoleShape::circle;
  const std::vector<Vertex> polygon = circle ? std::vector<Vertex>() : hole_polygon(hole);
  const Vertex c = circle ? hole.center : centroid(polygon);
  const HoleRing ring = make_ring(d, far_size, polygon, c);
  CellList cells;
  add_ring_cells(ring, cells);
  add_outer_cells(d, ring, far_size, cells);

  GridTools::invert_all_negative_measure_cells(cells.vertices, cells.cells);
  GridTools::consistently_order_cells(cells.cells);
  mesh.create_triangulation(cells.vertices, cells.cells, SubCellData());
  set_boundary_ids(d, mesh, circle);
  if (circle)
    mesh.set_manifold(1, PolarManifold<2>(Point<2>(c[0], c[1])));
}

double longest_edge(const Triangulation<2>::active_cell_iterator& cell)
{
  double h = 0.0;
  for (const unsigned int f : cell->face_indices())
    h = std::max(h, cell->face(f)->diameter());
  return h;
}

/// Refines until every element is at most min(far size, h_hole + (ratio - 1) d).
void grade_towards_hole(const HoleDescription& hole, const double far_size, Triangulation<2>& mesh)
{
  const double h_hole = hole.element_size > 0.0 ? std::min(hole.element_size, far_size) : far_size;
  for (unsigned int pass = 0; pass < 40; ++pass)
  {
    // A distributed mesh (p4est) flags its own cells and refines when any rank flagged one.
    bool refine = false;
    for (const auto& cell : mesh.active_cell_iterators())
    {
      if (!cell->is_locally_owned())
        continue;
      const Point<2> p = cell->center();
      const double distance = std::max(0.0, distance_from_hole(hole, p[0], p[1]));
      const double target = std::min(far_size, h_hole + (hole.growth_ratio - 1.0) * distance);
      if (longest_edge(cell) > target * (1.0 + 1e-9))
      {
        cell->set_refine_flag();
        refine = true;
      }
    }
    if (!Utilities::MPI::logical_or(refine, mesh.get_communicator()))
      return;
    mesh.execute_coarsening_and_refinement();
  }
}

void read_gmsh(const FarFieldDescription& d, Triangulation<2>& mesh)
{
  const std::string& file = d.mesh_file.file;
  std::ifstream in(file);
  require(std::filesystem::is_regular_file(file) && in,
          "mesh.file = '" + file + "': cannot open the file, expected a Gmsh .msh file");
  GridIn<2> grid_in;
  grid_in.attach_triangulation(mesh);
  try
  {
    grid_in.read_msh(in);
  }
  catch (const ExceptionBase& e)
  {
    // deal.II's own words only ("Additional information"), on one line: not its file, line and
    // stack trace.
    std::ostringstream info;
    e.print_info(info);
    std::string words;
    std::istringstream in_words(info.str());
    for (std::string word; in_words >> word;)
      words += (words.empty() ? "" : " ") + word;
    throw InputError("far field: mesh.file = '" + file +
                     "': not a mesh deal.II reads (expected ASCII Gmsh msh 2 or 4 of "
                     "quadrilaterals): " +
                     words);
  }

  std::map<unsigned int, BoundaryPart> part_of_tag;
  for (const auto& [part, tag] : d.mesh_file.parts)
  {
    const auto [it, inserted] = part_of_tag.emplace(tag, part);
    require(inserted, std::string("mesh.parts.") + name_of(part) + " = " + std::to_string(tag) +
                          ": the tag is also given to '" + name_of(it->second) +
                          "', expected one tag per part");
  }
  std::set<unsigned int> found;
  for (const auto& cell : mesh.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary())
        found.insert(cell->face(f)->boundary_id());
  for (const auto& [part, tag] : d.mesh_file.parts)
    if (found.count(tag) == 0)
    {
      std::string tags;
      for (const unsigned int t : found)
        if (t != 0)
          tags += (tags.empty() ? "" : ", ") + std::to_string(t);
      throw InputError(std::string("far field: mesh.parts.") + name_of(part) + " = " +
                       std::to_string(tag) + ": no boundary line of '" + file +
                       "' has this physical tag, expected one of: " +
                       (tags.empty() ? std::string("(none)") : tags));
    }
  for (const auto& cell : mesh.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary())
      {
        const auto part = part_of_tag.find(cell->face(f)->boundary_id());
        cell->face(f)->set_boundary_id(part == part_of_tag.end() ? untagged_boundary_id
                                                                 : boundary_id_of(part->second));
      }
}

} // namespace

types::boundary_id boundary_id_of(const BoundaryPart part)
{
  switch (part)
  {
  case BoundaryPart::left:
    return 0;
  case BoundaryPart::right:
    return 1;
  case BoundaryPart::bottom:
    return 2;
  case BoundaryPart::top:
    return 3;
  case BoundaryPart::hole:
    return 4;
  }
  return untagged_boundary_id;
}

double distance_from_hole(const HoleDescription& hole, const double x, const double y)
{
  if (hole.shape == HoleShape::none)
    return std::numeric_limits<double>::infinity();
  if (hole.shape == HoleShape::circle)
    return std::hypot(x - hole.center[0], y - hole.center[1]) - hole.radius;
  const std::vector<Vertex> polygon = hole_polygon(hole);
  const Vertex p{{x, y}};
  double distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i)
    distance =
        std::min(distance, distance_to_segment(p, polygon[i], polygon[(i + 1) % polygon.size()]));
  return inside_polygon(p, polygon) ? -distance : distance;
}

void make_far_field_mesh(const FarFieldDescription& d, const double far_size,
                         Triangulation<2>& mesh)
{
  if (!d.mesh_file.file.empty())
  {
    require(d.hole.shape == HoleShape::none,
            "mesh.file and hole are both given, expected one of them (a Gmsh mesh brings its "
            "own holes)");
    read_gmsh(d, mesh);
    return;
  }
  if (d.hole.shape == HoleShape::none)
  {
    const double lx = d.upper[0] - d.lower[0];
    const double ly = d.upper[1] - d.lower[1];
    GridGenerator::subdivided_hyper_rectangle(
        mesh, {element_intervals(lx, far_size), element_intervals(ly, far_size)},
        Point<2>(d.lower[0], d.lower[1]), Point<2>(d.upper[0], d.upper[1]), true);
    return;
  }
  check_hole(d);
  mesh.set_mesh_smoothing(Triangulation<2>::limit_level_difference_at_vertices);
  make_coarse_hole_mesh(d, far_size, mesh);
  grade_towards_hole(d.hole, far_size, mesh);
}

} // namespace ddafem::fem
