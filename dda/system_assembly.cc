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
    equations.matrix.set_zero();
  equations.rhs.setZero();
  // Loads and supports are evaluated at the step's end (the clock stands still in a static stage).
  const double t1 = mode == StageMode::static_equilibrium ? current_time : current_time + dt;
  prepare_dashpots(dt);
  add_block_terms(dt, with_matrix);
  StepSystem step{equations.matrix, equations.rhs};
  point_set.assemble(*this, step, t1, with_matrix);
  boundary_set.assemble(
      boundary_input(current_time, t1), scheme.coefficients, dt,
      [&](std::size_t i) { return step_start(i, dt); }, step, with_matrix);
  bonded.assemble(*this, model, dashpots, step, with_matrix);
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->assemble(*this, step, with_matrix);
}

void System::add_block_terms(double dt, bool with_matrix)
{
  // Blocks: inertia c M and elasticity; the inertia force of the block's past (v0, a0, r0), the
  // accumulated stress and gravity on the right-hand side.
  const double mass_factor = scheme.coefficients.mass_factor(dt);
  equations.masses.resize(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    const Block& b = blocks[i];
    const PolygonMoments& g = linearisation_moments(b);
    const double density = block_density(b);
    const Matrix6& m = equations.masses[i] = mass_matrix(g, density);
    // The dashpot beta K_e on the strain rates (dda/damping.h).
    const double beta = dashpot_factor(dashpots, model.materials[b.material].damping);
    auto f = equations.rhs.segment<6>(6 * i);
    if (with_matrix || beta > 0.0)
    {
      const Matrix6 k = elastic_stiffness(g.area, materials.elasticity[b.material]);
      if (with_matrix)
      {
        equations.matrix.diagonal(i).noalias() += mass_factor * m;
        equations.matrix.diagonal(i).noalias() += k;
        if (beta > 0.0)
          equations.matrix.diagonal(i).noalias() += (dashpots.velocity_factor * beta) * k;
      }
      if (beta > 0.0)
        f -= beta * (k * dashpots.offsets[i]);
    }
    f += inertia_force(scheme.coefficients, m, step_start(i, dt), dt);
    f += stress_force(g.area, b.stress) + body_force(g.area, density, model.gravity);
  }
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
  const BoundaryEdge& e = boundary_set.edges[k];
  return boundary_stability(model.boundaries[e.boundary].type, e, mass_of(e.block), dt);
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

void System::set_matrix_structure(std::vector<std::pair<std::size_t, std::size_t>> couplings)
{
  // The tied body couples every pair of blocks with tie points (its condensed stiffness is
  // dense over them): those pairs, sorted, merged into the contacts' sorted couplings in one
  // pass (a sort of both took 2.5 % of a tunnel's run).
  const std::vector<std::pair<std::size_t, std::size_t>> tied_block_pairs = tie_set.block_pairs();
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
  const bool structure_changed = equations.set_couplings(blocks.size(), std::move(couplings));
  bonded.find_couplings(*this, structure_changed);
}

std::size_t System::coupling_of(std::size_t i, std::size_t j) const
{
  return equations.coupling_of(i, j);
}

} // namespace ddafem::dda
