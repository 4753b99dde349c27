// The type of a plane body wave: the blocks' boundary input (dda::BoundaryInput), the far
// field's incident wave (fem::IncidentWave) and the tunnel scene's wave share it.
#pragma once

#include "common/enum_names.h"

#include <array>

namespace ddafem
{
/// A vertically incident plane wave's type: its particle velocity is vertical (P) or
/// horizontal (SV).
enum class WaveType
{
  p,
  sv
};

constexpr std::array<EnumName<WaveType>, 2> enum_names(WaveType)
{
  return {{{WaveType::p, "p"}, {WaveType::sv, "sv"}}};
}
} // namespace ddafem
