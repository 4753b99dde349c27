#include "dda/block_set.h"

#include "common/input_error.h"
#include "dda/submatrices.h"
#include "dda/system_helpers.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ddafem::dda
{
namespace
{
std::vector<Block> make_blocks(const ModelDescription& model)
{
  std::vector<Block> blocks;
  for (const BlockDescription& bd : model.blocks)
  {
    blocks.emplace_back(bd.material, bd.vertices);
    Block& b = blocks.back();
    b.velocity.head<2>() = bd.initial_velocity;
    b.stress = bd.initial_stress;
  }
  if (blocks.empty())
    throw InputError("the model has no blocks: expected at least one entry in `blocks`");
  return blocks;
}

} // namespace

BlockSet::BlockSet(const ModelDescription& model_)
    : list(make_blocks(model_)), materials(block_materials(model_)), held(list.size(), false),
      removed(list.size(), false), model(model_)
{
}

std::vector<std::string> block_names(const ModelDescription& model)
{
  std::vector<std::string> names;
  for (std::size_t i = 0; i < model.blocks.size(); ++i)
    names.push_back(model.blocks[i].origin.empty() ? "block " + std::to_string(i)
                                                   : model.blocks[i].origin);
  return names;
}

MaterialPoint BlockSet::attach(const Point& p, const std::string& what) const
{
  const double tol = 1e-9 * model_size(list);
  for (std::size_t i = 0; i < list.size(); ++i)
    if (locate_point(list[i].vertices, p, tol) != PointLocation::outside)
      return {i, p, p};
  std::ostringstream s;
  s << what << " at (" << p.x() << ", " << p.y()
    << ") lies outside every block: expected a point inside or on a block";
  throw InputError(s.str());
}

Matrix26 BlockSet::point_matrix(const MaterialPoint& p) const
{
  const Block& b = list[p.block];
  return small_displacement() ? displacement_matrix(b.initial_centroid, p.initial)
                              : displacement_matrix(b.moments.centroid, p.position);
}

Vector2 BlockSet::point_displacement(const MaterialPoint& p, const Vector6& d) const
{
  const Block& b = list[p.block];
  return small_displacement() ? displacement_at(b.initial_centroid, p.initial, d)
                              : displacement_at(b.moments.centroid, p.position, d);
}

double BlockSet::density(const Block& b) const
{
  const double density = model.materials[b.material].density;
  if (small_displacement())
    return density; // the linearisation area is the initial one
  return density * (b.initial_moments.area / b.moments.area);
}

double BlockSet::kinetic_energy(const Block& b) const
{
  return 0.5 * b.velocity.dot(mass_matrix(linearisation_moments(b), density(b)) * b.velocity);
}

double BlockSet::largest_vertex_displacement(const Eigen::VectorXd& d) const
{
  // The largest squared length, one square root at the end (sqrt is monotonic: the same value).
  double largest = 0.0;
  for (std::size_t i = 0; i < list.size(); ++i)
  {
    const Block& b = list[i];
    const Vector6 di = d.segment<6>(6 * i);
    const std::vector<Point>& v = small_displacement() ? b.initial_vertices : b.vertices;
    const Point& c = small_displacement() ? b.initial_centroid : b.moments.centroid;
    for (const Point& x : v)
      largest = std::max(largest, displacement_at(c, x, di).squaredNorm());
  }
  return std::sqrt(largest);
}

std::vector<BlockSnapshot> BlockSet::snapshot() const
{
  std::vector<BlockSnapshot> out;
  out.reserve(list.size());
  for (std::size_t i = 0; i < list.size(); ++i)
  {
    const Block& b = list[i];
    out.push_back({i, b.material, b.vertices, b.displacement(), b.velocity.head<2>(), b.stress});
  }
  return out;
}

void BlockSet::advance_states(const Eigen::VectorXd& d, double dt,
                              const std::vector<Matrix6>& masses, StepScheme& scheme, bool dynamic)
{
  for (std::size_t i = 0; i < list.size(); ++i)
  {
    Block& b = list[i];
    const Vector6 di = d.segment<6>(6 * i);
    const Matrix6& m = masses[i]; // the attempt's assembly: the same configuration
    const KinematicState end =
        advance_state(scheme.coefficients, m, scheme.start(b, i, dt), di, dt);
    b.velocity = end.velocity;
    b.acceleration = scheme.composite_acceleration(i, m, end, dynamic);
    b.force = end.force;
    if (removed[i])
    {
      b.velocity.setZero();
      b.acceleration.setZero();
      b.force.setZero();
    }
    b.apply_increment(di, materials.elasticity[b.material], small_displacement());
  }
}

void BlockSet::set_at_rest()
{
  for (Block& b : list)
  {
    b.velocity.setZero();
    b.acceleration.setZero();
    b.force.setZero();
  }
}

} // namespace ddafem::dda
