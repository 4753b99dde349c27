// The model's energy balance (EnergyBalance) and the System's ledger of what enters it between
// steps: the works done on the blocks, the energy at the start and the kinetic energy that left
// with removed blocks [J]. The stored energies are measured from the blocks when asked for
// (System::energy); the works are summed step by step (System::add_work_of_step).
#pragma once

namespace ddafem::dda
{
/// Energies of the model [J]. Conservation: kinetic + strain + spring = initial +
/// work_of_loads + work_of_supports + work_of_boundaries + work_of_damping - dissipated, where
/// `dissipated` is the residual: the algorithmic damping of the integrator (zero for trapezoidal
/// Newmark on a linear model).
struct EnergyBalance
{
  double kinetic = 0.0;       ///< sum of v^T M v / 2
  double strain = 0.0;        ///< block elastic energy, sum of area sigma^T C^-1 sigma / 2
  double spring = 0.0;        ///< joint springs, fixed-point penalty springs and bolts (N^2 / 2k)
  double work_of_loads = 0.0; ///< point loads and gravity, since t = 0
  double work_of_supports = 0.0; ///< done by prescribed motions of fixed points, since t = 0
  /// Done by the viscous boundaries on the blocks since t = 0: negative when they absorb.
  double work_of_boundaries = 0.0;
  /// Done by the ties to a tied body (the far field) on the blocks since t = 0: the energy that
  /// crossed the interface into the blocks (negative when it left them).
  double work_of_ties = 0.0;
  double work_of_damping = 0.0; ///< done by the rock's dashpots (dda/damping.h), negative
  /// Kinetic energy that left with blocks removed in motion (fallen debris, see
  /// SettleCriterion::remove_fallen), since t = 0.
  double removed = 0.0;
  double initial = 0.0;    ///< kinetic + strain + spring at t = 0
  double dissipated = 0.0; ///< initial + works - removed - (kinetic + strain + spring)

  double stored() const { return kinetic + strain + spring; }
};

/// The sums kept between steps [J], since t = 0 or since a dynamic stage began after a static
/// one (EnergyBalance has their meaning).
struct EnergyLedger
{
  double loads = 0.0;         ///< EnergyBalance::work_of_loads
  double supports = 0.0;      ///< EnergyBalance::work_of_supports
  double boundaries = 0.0;    ///< EnergyBalance::work_of_boundaries
  double damping = 0.0;       ///< EnergyBalance::work_of_damping
  double removed = 0.0;       ///< EnergyBalance::removed
  double initial = 0.0;       ///< EnergyBalance::initial
  double largest_input = 0.0; ///< the largest loads + supports so far

  /// A dynamic stage measures from the state reached, whose stored energy is `stored`.
  void restart(const double stored)
  {
    loads = supports = boundaries = damping = 0.0;
    largest_input = 0.0;
    initial = stored;
  }
  /// Its sums into `e` (the stored energies and the ties' work aside).
  void fill(EnergyBalance& e) const
  {
    e.work_of_loads = loads;
    e.work_of_supports = supports;
    e.work_of_boundaries = boundaries;
    e.work_of_damping = damping;
    e.removed = removed;
    e.initial = initial;
  }
};

} // namespace ddafem::dda
