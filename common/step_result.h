// What one step of a body the blocks step with gives back: the far field (fem::ElasticWaveModel,
// fem::DistributedWaveModel, the free-field column) and a tied body (dda::TiedBody, which
// coupling::FarFieldTies implements). The one result type that crosses the coupling (issue 55):
// the System turns a failed one into its own dda::StepStatus, a solver_failure with the message
// and the time, which the TimeStepper acts on (cuts the step). A numerical outcome, not an
// exception.
#pragma once

#include <string>
#include <utility>

namespace ddafem
{
struct StepResult
{
  bool taken = true; ///< the step was taken (the default: a StepResult{} is a success)
  std::string why;   ///< when not taken: why, e.g. the solver's message

  /// A step that could not be taken, and why.
  static StepResult failure(std::string why) { return {false, std::move(why)}; }
};

} // namespace ddafem
