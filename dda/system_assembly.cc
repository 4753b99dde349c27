// Phase 3 of the step: the matrix and right-hand side of blocks, loads, fixed points,
// boundaries and joints, in the configuration the step is linearised about (the contacts' terms
// of phase 4 are in dda/contact/contact_terms.cc).
#include "dda/system.h"

#include "dda/submatrices.h"
#include "dda/system_helpers.h"

namespace ddafem::dda
{
void System::assemble(double dt, bool with_matrix)
{
  if (with_matrix)
    matrix.set_zero();
  rhs.setZero();
  // Loads and supports are evaluated at the step's end (the clock stands still in a static stage).
  const double t1 = mode == StageMode::static_equilibrium ? current_time : current_time + dt;
  prepare_dashpots(dt);
  add_block_terms(dt, with_matrix);
  add_point_terms(t1, with_matrix);
  add_boundary_terms(dt, t1, with_matrix);
  add_joint_terms(with_matrix);
  StepSystem step{matrix, rhs};
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->assemble(*this, step, with_matrix);
}

void System::add_block_terms(double dt, bool with_matrix)
{
  // Blocks: inertia c M and elasticity; the inertia force of the block's past (v0, a0, r0), the
  // accumulated stress and gravity on the right-hand side.
  const double mass_factor = step_integration.mass_factor(dt);
  step_masses.resize(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    const Block& b = blocks[i];
    const PolygonMoments& g = linearisation_moments(b);
    const double density = block_density(b);
    const Matrix6& m = step_masses[i] = mass_matrix(g, density);
    // The dashpot beta K_e on the strain rates (dda/damping.h).
    const double beta = dashpot_factor(dashpots, model.materials[b.material].damping);
    auto f = rhs.segment<6>(6 * i);
    if (with_matrix || beta > 0.0)
    {
      const Matrix6 k = elastic_stiffness(g.area, elasticity[b.material]);
      if (with_matrix)
      {
        matrix.diagonal(i).noalias() += mass_factor * m;
        matrix.diagonal(i).noalias() += k;
        if (beta > 0.0)
          matrix.diagonal(i).noalias() += (dashpots.velocity_factor * beta) * k;
      }
      if (beta > 0.0)
        f -= beta * (k * dashpots.offsets[i]);
    }
    f += inertia_force(step_integration, m, step_start(i, dt), dt);
    f += stress_force(g.area, b.stress) + body_force(g.area, density, model.gravity);
  }
}

void System::add_point_terms(double t1, bool with_matrix)
{
  // Point loads at their material points.
  for (const AttachedLoad& l : loads)
    rhs.segment<6>(6 * l.point.block).noalias() +=
        point_matrix(l.point).transpose() * (l.force * l.function.value(t1));

  // Fixed points: penalty spring k |x + T d - X(t1)|^2 / 2.
  for (const AttachedFixedPoint& f : fixed_points)
  {
    const Matrix26 t = point_matrix(f.point);
    if (with_matrix)
      matrix.diagonal(f.point.block).noalias() += f.stiffness * t.transpose() * t;
    rhs.segment<6>(6 * f.point.block).noalias() +=
        f.stiffness * t.transpose() * (f.target(t1) - f.point.position);
  }
}

void System::add_boundary_terms(double dt, double t1, bool with_matrix)
{
  // Viscous boundaries at their edge midpoints, with the incident wave's input force; in a
  // static stage their supports hold the edges instead (springs to the anchors plus the load),
  // in a dynamic one the supports' loads stay on as constant forces.
  const bool is_static = mode == StageMode::static_equilibrium;
  for (std::size_t k = 0; k < boundary_edges.size(); ++k)
  {
    boundary_steps[k] = {};
    if (is_static)
      continue;
    const BoundaryEdge& e = boundary_edges[k];
    const KinematicState start = step_start(e.block, dt);
    const Matrix26 t = point_matrix(e.midpoint);
    boundary_steps[k] = boundary_step(
        model.boundaries[e.boundary].type, e, boundary_normal(e), block_mass(blocks[e.block]), dt,
        step_integration.beta, step_integration.gamma, t * start.velocity, t * start.acceleration);
    if (with_matrix)
      matrix.diagonal(e.block).noalias() += t.transpose() * boundary_steps[k].k * t;
    rhs.segment<6>(6 * e.block).noalias() +=
        t.transpose() * (boundary_steps[k].f + input_force(e, t1));
  }
  for (const Support& s : supports)
  {
    const Matrix26 t = point_matrix(s.point);
    if (is_static && with_matrix)
      matrix.diagonal(s.point.block).noalias() += t.transpose() * s.stiffness * t;
    rhs.segment<6>(6 * s.point.block).noalias() += t.transpose() * (is_static ? s.force() : s.load);
  }
}

void System::add_joint_terms(bool with_matrix)
{
  // Bonded joints: springs K_s on the gap g + T_b d_b - T_a d_a, with g = x_b - x_a, plus the
  // preloads.
  for (const Joint& j : joints)
  {
    const Vector2 tangent = j.tangent(small_displacement());
    const Vector2 n = Joint::normal_of(tangent);
    const JointMaterial& jm = model.joint_materials[j.joint_material];
    const Eigen::Matrix2d springs = joint_spring_matrix(jm, n, tangent);
    // With a dashpot beta K_s on the relative velocity (dda/damping.h): (1 + c_v beta) K_s.
    const double beta = dashpot_factor(dashpots, jm.damping);
    const Eigen::Matrix2d ks =
        beta > 0.0 ? Eigen::Matrix2d((1.0 + dashpots.velocity_factor * beta) * springs) : springs;
    for (const JointPoint& p : j.points)
    {
      const Matrix26 ta = point_matrix(p.on_a);
      const Matrix26 tb = point_matrix(p.on_b);
      if (beta > 0.0)
      {
        const Vector2 offset = point_displacement(p.on_b, dashpots.offsets[j.block_b]) -
                               point_displacement(p.on_a, dashpots.offsets[j.block_a]);
        const Vector2 force = beta * (springs * offset);
        rhs.segment<6>(6 * j.block_a).noalias() += ta.transpose() * force;
        rhs.segment<6>(6 * j.block_b).noalias() -= tb.transpose() * force;
      }
      if (with_matrix)
      {
        const Matrix26 ks_ta = ks * ta;
        const Matrix26 ks_tb = ks * tb;
        matrix.diagonal(j.block_a).noalias() += ta.transpose() * ks_ta;
        matrix.diagonal(j.block_b).noalias() += tb.transpose() * ks_tb;
        matrix.upper(j.coupling).noalias() -= ta.transpose() * ks_tb;
      }
      const Vector2 force = springs * (p.on_b.position - p.on_a.position) + p.normal_preload * n +
                            p.shear_preload * tangent;
      rhs.segment<6>(6 * j.block_a).noalias() += ta.transpose() * force;
      rhs.segment<6>(6 * j.block_b).noalias() -= tb.transpose() * force;
    }
  }
}

void System::add_hold_terms()
{
  for (std::size_t i = 0; i < blocks.size(); ++i)
    if (is_held(i))
      matrix.diagonal(i).diagonal() *= 1.0 + 1e8;
}

Vector2 System::input_force(const BoundaryEdge& e, double t) const
{
  const BoundaryDescription& b = model.boundaries[e.boundary];
  if (!b.has_input)
    return Vector2::Zero();
  const Vector2 n = boundary_normal(e), tangent(-n.y(), n.x());
  const double v = b.input.velocity.value(t);
  const Vector2 v_in = b.input.type == BoundaryInput::Type::p ? Vector2(0.0, v) : Vector2(v, 0.0);
  return 2.0 * (e.cn * n.dot(v_in) * n + e.ct * tangent.dot(v_in) * tangent);
}

Vector2 System::boundary_normal(const BoundaryEdge& e) const
{
  const Block& b = blocks[e.block];
  const std::vector<Point>& v = small_displacement() ? b.initial_vertices : b.vertices;
  const Vector2 t = (v[(e.edge + 1) % v.size()] - v[e.edge]).normalized();
  return Vector2(t.y(), -t.x());
}

double System::block_mass(const Block& b) const
{
  return model.materials[b.material].density * b.initial_moments.area;
}

double System::block_density(const Block& b) const
{
  const double density = model.materials[b.material].density;
  if (small_displacement())
    return density; // the linearisation area is the initial one
  return density * (b.initial_moments.area / b.moments.area);
}

BoundaryStability System::stability_of(std::size_t k, double dt) const
{
  const BoundaryEdge& e = boundary_edges[k];
  return boundary_stability(model.boundaries[e.boundary].type, e, block_mass(blocks[e.block]), dt);
}

const PolygonMoments& System::linearisation_moments(const Block& b) const
{
  return small_displacement() ? b.initial_moments : b.moments;
}

Matrix26 System::point_matrix(const MaterialPoint& p) const
{
  const Block& b = blocks[p.block];
  return small_displacement() ? displacement_matrix(b.initial_centroid, p.initial)
                              : displacement_matrix(b.moments.centroid, p.position);
}

Vector2 System::point_displacement(const MaterialPoint& p, const Vector6& d) const
{
  const Block& b = blocks[p.block];
  return small_displacement() ? displacement_at(b.initial_centroid, p.initial, d)
                              : displacement_at(b.moments.centroid, p.position, d);
}

void System::refresh_joint_lists()
{
  if (joint_lists.revision == joint_revision)
    return;
  joint_lists.revision = joint_revision;
  joint_lists.joined.clear();
  for (const Joint& j : joints)
    joint_lists.joined.emplace_back(j.block_a, j.block_b);
  // An element between two blocks (a bolt, a frame) couples them in the matrix like a joint
  // (not in contact detection).
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->add_couplings(joint_lists.joined);
  std::sort(joint_lists.joined.begin(), joint_lists.joined.end());
}

void System::set_matrix_structure(std::vector<std::pair<std::size_t, std::size_t>> couplings)
{
  // The tied body couples every pair of blocks with tie points (its condensed stiffness is
  // dense over them): those pairs, sorted by construction (tie_blocks is), merged into the
  // contacts' sorted couplings in one pass (a sort of both took 2.5 % of a tunnel's run).
  std::vector<std::pair<std::size_t, std::size_t>> tied_block_pairs;
  tied_block_pairs.reserve(tie_blocks.size() * tie_blocks.size() / 2);
  for (std::size_t i = 0; i < tie_blocks.size(); ++i)
    for (std::size_t j = i + 1; j < tie_blocks.size(); ++j)
      tied_block_pairs.emplace_back(tie_blocks[i], tie_blocks[j]);
  if (!std::is_sorted(couplings.begin(), couplings.end()))
    std::sort(couplings.begin(), couplings.end());
  if (!tied_block_pairs.empty())
  {
    std::vector<std::pair<std::size_t, std::size_t>> merged(couplings.size() +
                                                            tied_block_pairs.size());
    std::merge(couplings.begin(), couplings.end(), tied_block_pairs.begin(), tied_block_pairs.end(),
               merged.begin());
    couplings = std::move(merged);
  }
  couplings.erase(std::unique(couplings.begin(), couplings.end()), couplings.end());
  if (couplings != coupling_pairs || matrix.n_blocks() != blocks.size())
  {
    coupling_pairs = std::move(couplings);
    matrix = BlockSparseMatrix(blocks.size(), coupling_pairs);
    coupling_rows.assign(blocks.size() + 1, 0);
    for (const auto& pair : coupling_pairs)
      ++coupling_rows[pair.first + 1];
    for (std::size_t i = 0; i < blocks.size(); ++i)
      coupling_rows[i + 1] += coupling_rows[i];
  }
  else if (joint_couplings_revision == joint_revision)
    return; // the joints' couplings are where they were
  for (Joint& j : joints)
    j.coupling = coupling_of(j.block_a, j.block_b);
  joint_couplings_revision = joint_revision;
}

std::size_t System::coupling_of(std::size_t i, std::size_t j) const
{
  // Within the couplings of the lower block (all of them lie in its row): the same index as a
  // search of all couplings, at the cost of a few comparisons.
  const auto key = std::make_pair(std::min(i, j), std::max(i, j));
  const auto row = coupling_pairs.begin();
  return static_cast<std::size_t>(
      std::lower_bound(row + coupling_rows[key.first], row + coupling_rows[key.first + 1], key) -
      row);
}
} // namespace ddafem::dda
