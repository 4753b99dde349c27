// What a scene may take of this machine, and the estimates that refuse one too large for it
// before anything big is allocated (issue 20).
#pragma once

#include <cstddef>
#include <string>

namespace ddafem
{
/// Peak memory [bytes] of the parts of a run, per unit, measured on this project's examples
/// (docs/design.md, "Bounded resources") with a margin of about 1.4:
/// - blocks: 17 kB per block for a 20,626-block bonded rock mass with its direct solver,
///   28 kB for the 2,022-block collapsing wall with its ~12,000 contacts; 24 kB each;
/// - far field: 3.1 to 3.2 kB per DOF (32,882 to 515,522 DOFs of the shear column, degree 2,
///   with KLU) above 150 MB for deal.II and Trilinos; 4 kB each.
struct MemoryModel
{
  static constexpr double base = 30e6;             ///< the program alone [bytes]
  static constexpr double per_block = 24e3;        ///< [bytes per block]
  static constexpr double far_field_base = 150e6;  ///< deal.II, Trilinos, the module [bytes]
  static constexpr double per_far_field_dof = 4e3; ///< [bytes per DOF]
  static double of_blocks(double n_blocks) { return base + per_block * n_blocks; }
  /// While a rock mass is generated, its CGAL arrangement [bytes per edge] (measured 4.4 kB a
  /// trace for 80,000 short traces, 1.7 kB a side for a circle of 38,500 sides)
  static constexpr double per_arrangement_edge = 4.5e3;
  static double of_far_field(double n_dofs) { return far_field_base + per_far_field_dof * n_dofs; }
  static double of_arrangement(double n_edges) { return base + per_arrangement_edge * n_edges; }
  /// The inverses: how many blocks, far-field DOFs, `bytes` hold (negative below the base).
  static double blocks_within(double bytes) { return (bytes - base) / per_block; }
  static double arrangement_edges_within(double bytes)
  {
    return (bytes - base) / per_arrangement_edge;
  }
  static double far_field_dofs_within(double bytes)
  {
    return (bytes - far_field_base) / per_far_field_dof;
  }
};

/// The memory a scene may need at most [bytes], and where that limit comes from.
struct ResourceLimits
{
  double memory = 0.0; ///< [bytes]; <= 0: no limit
  std::string source;  ///< e.g. "the 23.7 GB available on this machine"

  /// 90 % of MemAvailable in /proc/meminfo (no limit where it cannot be read).
  static ResourceLimits of_this_machine();
  /// A limit the user gave (--max-memory), as `text` ("8G", "500M", "2e9"); throws InputError
  /// naming the option and the value if it is not a positive size.
  static ResourceLimits given(const std::string& text);

  /// Whether `bytes` fits.
  bool fits(double bytes) const { return memory <= 0.0 || bytes <= memory; }
  /// "about 31 GB, more than the 21.4 GB available on this machine (--max-memory sets another
  /// limit)" for an estimate of `bytes`.
  std::string too_much(double bytes) const;
};

/// About how many DOFs a generated far-field mesh has, before it is made: `area` [m^2] over
/// the element size h [m] squared, plus the ring graded from the hole's element size h0 [m]
/// outwards (h(d) = h0 + (g - 1) d up to h): 6 times the hole's perimeter [m] / (g - 1)
/// (1 / h0 - 1 / h) cells (the quadtree's refinement, measured on the examples); 2 p^2 DOFs per
/// cell of FE_Q(p). Without refinement at the hole, h0 = 0.
double estimate_far_field_dofs(double area, double h, double hole_perimeter, double h0,
                               double growth_ratio, unsigned degree);

/// `bytes` as "812 MB" or "31.2 GB" (decimal units).
std::string format_bytes(double bytes);

} // namespace ddafem
