// The restart of generalized-alpha where friction turns around within a step (the turns found by
// ContactSet::scan_reversals, dda/contact/contact_trials.cc).
#include "dda/submatrices.h"
#include "dda/system.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>

namespace ddafem::dda
{

void System::restart_at_friction_jumps(const std::vector<std::size_t>& turning)
{
  const auto add = [this](std::size_t i, const Vector6& jump)
  {
    Block& b = block_set.list[i];
    std::vector<StepScheme::StateBeforeJump>& before = scheme.friction_jumps;
    if (std::none_of(before.begin(), before.end(),
                     [i](const StepScheme::StateBeforeJump& s) { return s.block == i; }))
      before.push_back({i, b.acceleration, b.force});
    const Matrix6 m = mass_matrix(block_set.linearisation_moments(b), block_set.density(b));
    // The Newmark schemes and Bathe's first half restart the translation only: the jump's
    // moment would set off the block's stiff rocking on its contacts (whose normal forces take
    // that moment up at once in the rigid limit), which they damp little or not at all
    // (two-way sliding at 4 Hz with Bathe's scheme: 0.65% with the translation, 1.07% with the
    // full restart). Generalized-alpha at rho_inf 0.2 damps it.
    Vector6 applied = jump;
    if (scheme.coefficients.alpha_f == 0.0 || scheme.integrator == Integrator::bathe)
      applied.tail<4>().setZero();
    b.force += applied;
    b.acceleration += m.ldlt().solve(applied);
  };
  contact_set.add_friction_jumps(turning, add);
}

} // namespace ddafem::dda
