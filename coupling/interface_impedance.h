// The impedance contrast at the interface of a coupled model: the tied blocks with the joints
// behind them as one continuum against the far field's material. A contrast reflects part of
// every wave that crosses the interface (`check` and `run` warn above 1%).
#pragma once

#include "coupling/far_field_ties.h"
#include "dda/model_description.h"
#include "dda/system.h"

#include <optional>

namespace ddafem::coupling
{
/// The tied blocks with their joints as one continuum, against the far field's material.
struct InterfaceImpedance
{
  double blocks_modulus = 0.0;    ///< E_eff of the tied blocks and the joints behind them [Pa]
  double far_field_modulus = 0.0; ///< [Pa]
  double reflection = 0.0;        ///< of a normally incident plane wave [-]
};

/// The reflection |1 - r| / (1 + r) of a normally incident plane wave between materials of equal
/// density with moduli `blocks_modulus` and `far_field_modulus` [Pa]: the impedance ratio is
/// r = sqrt(E_blocks / E_far).
InterfaceImpedance impedance_contrast(double blocks_modulus, double far_field_modulus);

/// E_eff (dda::jointed_block_modulus) per tied block, averaged over the tied length: L the tied
/// length, p that of `model`'s default joint material, d = area / L the block's depth behind
/// it; against `far_field_modulus` [Pa] (impedance_contrast). Nothing without `joints.default`.
std::optional<InterfaceImpedance> interface_impedance(const dda::ModelDescription& model,
                                                      const dda::System& system,
                                                      const FarFieldTies& ties,
                                                      double far_field_modulus);

} // namespace ddafem::coupling
