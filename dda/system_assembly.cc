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
  dashpots.prepare(block_set, scheme, dt, block_set.materials.damped && mode == StageMode::dynamic);
  add_block_terms(dt, with_matrix);
  point_set.assemble(block_set, equations, t1, with_matrix);
  boundary_set.assemble(
      {model, block_set.list, block_set, mode == StageMode::static_equilibrium, current_time, t1},
      scheme.coefficients, dt,
      [&](std::size_t i) { return scheme.start(block_set.list[i], i, dt); }, equations,
      with_matrix);
  bonded.assemble(block_set, model, dashpots, equations, with_matrix);
  for (const std::unique_ptr<ElementKind>& k : element_kinds)
    k->assemble(block_set, equations, with_matrix);
}

void System::add_block_terms(double dt, bool with_matrix)
{
  // Blocks: inertia c M and elasticity; the inertia force of the block's past (v0, a0, r0), the
  // accumulated stress and gravity on the right-hand side.
  const double mass_factor = scheme.coefficients.mass_factor(dt);
  equations.masses.resize(block_set.list.size());
  for (std::size_t i = 0; i < block_set.list.size(); ++i)
  {
    const Block& b = block_set.list[i];
    const PolygonMoments& g = block_set.linearisation_moments(b);
    const double density = block_set.density(b);
    const Matrix6& m = equations.masses[i] = mass_matrix(g, density);
    // The dashpot beta K_e on the strain rates (dda/damping.h).
    const double beta = dashpot_factor(dashpots, model.materials[b.material].damping);
    auto f = equations.rhs.segment<6>(6 * i);
    if (with_matrix || beta > 0.0)
    {
      const Matrix6 k = elastic_stiffness(g.area, block_set.materials.elasticity[b.material]);
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
    f += inertia_force(scheme.coefficients, m, scheme.start(block_set.list[i], i, dt), dt);
    f += stress_force(g.area, b.stress) + body_force(g.area, density, model.gravity);
  }
}

BoundaryStability stability_of(const System& system, std::size_t k, double dt)
{
  const BoundaryEdge& e = system.boundaries().edges[k];
  return boundary_stability(system.get_model().boundaries[e.boundary].type, e,
                            system.blocks().mass_of(e.block), dt);
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
  const bool structure_changed =
      equations.set_couplings(block_set.list.size(), std::move(couplings));
  bonded.find_couplings(equations, structure_changed);
}

} // namespace ddafem::dda
