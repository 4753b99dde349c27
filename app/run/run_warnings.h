// The words `check` and `run` use for what the libraries' engineering rules find: unstable
// viscous boundaries (dda/unstable_boundaries.h) and the suggested time step
// (dda/time_step_advice.h); the interface's impedance contrast is the module's
// (TiedFarField::impedance_warning).
#pragma once

#include "dda/system.h"
#include "dda/time_step_advice.h"

#include <cstddef>
#include <string>
#include <vector>

namespace ddafem
{
/// "ORIGIN (TYPE)" of boundary k, or "boundary k (TYPE)" without an origin.
std::string boundary_name(const dda::ModelDescription& model, std::size_t k);

/// One message per boundary whose edges are energy sources at dt [s]: how many, x and the dt
/// below which it absorbs.
std::vector<std::string> unstable_boundary_messages(const dda::System& system, double dt);

/// The rule behind dt_max in words, e.g. "a P wave crosses the smallest block in 1e-05 s".
std::string time_step_reason(const dda::TimeStepAdvice& advice);

} // namespace ddafem
