#include "app/run/run_warnings.h"

#include "common/format.h"

#include "dda/unstable_boundaries.h"

namespace ddafem
{

namespace
{
const char* boundary_type_name(dda::BoundaryType t)
{
  switch (t)
  {
  case dda::BoundaryType::free:
    return "free";
  case dda::BoundaryType::vb1:
    return "vb1";
  case dda::BoundaryType::vb2:
    return "vb2";
  case dda::BoundaryType::dashpot:
    return "dashpot";
  }
  return "";
}
} // namespace

std::string boundary_name(const dda::ModelDescription& model, std::size_t k)
{
  const dda::BoundaryDescription& b = model.boundaries[k];
  return (b.origin.empty() ? "boundary " + std::to_string(k) : b.origin) + " (" +
         boundary_type_name(b.type) + ")";
}

std::vector<std::string> unstable_boundary_messages(const dda::System& system, double dt)
{
  std::vector<std::string> messages;
  for (const dda::UnstableBoundary& u : dda::unstable_boundaries(system, dt))
    messages.push_back("dt = " + format_significant(dt) + " s makes " +
                       boundary_name(system.get_model(), u.boundary) + " an energy source on " +
                       std::to_string(u.n_sources) + " edge(s): x = c dt / m reaches " +
                       format_significant(u.x_max, 4) + " > " +
                       format_significant(dda::vb1_source_threshold(), 5) +
                       "; it absorbs only for dt < " + format_significant(u.dt_limit, 4) + " s");
  return messages;
}

std::string time_step_reason(const dda::TimeStepAdvice& advice)
{
  switch (advice.limit)
  {
  case dda::TimeStepLimit::block_transit:
    return "a P wave crosses the smallest block in " + format_significant(advice.transit, 3) + " s";
  case dda::TimeStepLimit::load_period:
    return "20 steps per period of the highest load frequency (" +
           format_significant(advice.max_frequency, 4) + " Hz)";
  case dda::TimeStepLimit::dda_damping:
    return "DDA's algorithmic damping costs < 5% amplitude at " +
           format_significant(advice.max_frequency, 4) + " Hz over a model crossing";
  }
  return "";
}

} // namespace ddafem
