// The step part of call k of a run of equal-dt System::advance calls in a dynamic stage, for
// tests that drive a System directly rather than through TimeStepper.
#pragma once
#include "dda/system.h"

#include <cstddef>

namespace ddafem::dda::step_parts
{
/// Bathe's composite scheme (the default integrator): first and second halves in turn from
/// k = 0, as TimeStepper takes them, each call a half step of its dt; every other integrator:
/// full steps.
inline StepPart of_call(const System& system, std::size_t k)
{
  if (system.get_model().time.integrator != Integrator::bathe)
    return StepPart::full;
  return k % 2 == 0 ? StepPart::first_half : StepPart::second_half;
}

} // namespace ddafem::dda::step_parts
