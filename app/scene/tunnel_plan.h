// The plan of a tunnel in jointed rock under a seismic wave (issue 10): from what a rock
// engineer knows (the opening, the joint sets, the depth, the wave, the accuracy wanted) the
// near field of blocks, its truncation (a deal.II far field, boundaries on the blocks or a ring
// of outer blocks), the element and block sizes, the time steps and the stages, each choice
// with its reason. app/scene/tunnel_scene.h writes the plan into a scene's sections.
#pragma once

#include "common/resource_limits.h"
#include "common/wave_type.h"
#include "dda/model_description.h"
#include "dda/rock_mass.h"

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace ddafem
{
using dda::Point;

/// How the model around the near field (the blocks) is truncated.
enum class TunnelTruncation
{
  /// (b) the blocks tied to a deal.II far field graded outward, Lysmer dashpots at its base
  /// (with the incident wave's input) and top, free-field columns at its sides
  hybrid,
  /// (a) blocks only: VB I (Bao et al. 2012) on the near field's edges, the wave input at its
  /// base
  vb1,
  /// (a') blocks only with the consistent dashpot on the near field's edges
  dashpot,
  /// (c) the hybrid with a far field so large that nothing it reflects comes back to the
  /// opening within the run
  reference,
  /// (c') blocks only out to the reference's extent: the near field inside a ring of bonded
  /// rectangular blocks with the rock mass's modulus, dashpots on the ring's outer edges, the
  /// wave input at its base
  blocks
};

constexpr std::array<EnumName<TunnelTruncation>, 5> enum_names(TunnelTruncation)
{
  return {{{TunnelTruncation::hybrid, "hybrid"},
           {TunnelTruncation::vb1, "vb1"},
           {TunnelTruncation::dashpot, "dashpot"},
           {TunnelTruncation::reference, "reference"},
           {TunnelTruncation::blocks, "blocks"}}};
}

/// The `tunnel` scene section as the scene reader read and validated it, with the numbers it
/// needs from the rest of the scene.
struct TunnelDescription
{
  std::string rock;            ///< name of the intact rock's material
  double density = 0.0;        ///< [kg/m^3]
  double youngs_modulus = 0.0; ///< of the intact rock [Pa]
  double poisson_ratio = 0.0;
  /// Normal spring p of `joints.default` [N/m] (each end of a joint), for the rock mass's
  /// modulus; 0 without a default joint material.
  double joint_normal_stiffness = 0.0;
  /// The joint sets, explicit joints, the opening (openings[0]), seed and chord tolerance; the
  /// region is the plan's near field.
  dda::RockMassDescription rock_mass;
  double depth = 0.0;    ///< of the opening's centre below the ground surface [m]
  double k0 = 0.5;       ///< horizontal over vertical in-situ stress [-]
  double gravity = 9.81; ///< [m/s^2], downwards (-y)
  WaveType wave_type = WaveType::sv;
  double wave_frequency = 0.0; ///< dominant frequency of the incident wave [Hz]
  double max_frequency = 0.0;  ///< highest frequency the model must carry [Hz]
  double wave_duration = 0.0;  ///< time from t = 0 to the end of the incident pulse [s]
  double size_factor = 4.0;    ///< near-field side over the opening's width [-]
  /// Explicit near field [lower, upper] instead of size_factor [m].
  std::optional<std::array<Point, 2>> near_field;
  TunnelTruncation truncation = TunnelTruncation::hybrid;
  double margin = 0.0;           ///< far field beyond the near field [m]; 0: chosen
  double reference_margin = 0.0; ///< the same for `reference` and `blocks` [m]; 0: chosen
  double points_per_wavelength = 10.0;
  double growth_ratio = 1.3;
  double window = 0.0;    ///< dynamic stage after the wave reaches the near field [s]; 0: chosen
  double dt = 0.0;        ///< [s]; 0: chosen
  double static_dt = 0.0; ///< [s]; 0: chosen
  double static_tolerance = 1e-5;
  long long static_max_steps = 5000;
  dda::ReleaseAction static_release = dda::ReleaseAction::fall; ///< stages[i].release, static stage
  bool settle = true;                ///< a settle stage after the wave (tunnel.settle.enabled)
  double settle_rest_speed = 1e-3;   ///< [m/s]
  double settle_rest_duration = 0.0; ///< [s]; 0: chosen
  double settle_max_duration = 0.0;  ///< [s]; 0: chosen
  bool settle_remove_fallen = true;  ///< SettleCriterion::remove_fallen
  /// The memory the scene may take: plan_tunnel refuses a plan estimated beyond it (InputError)
  /// before it generates the near field's blocks.
  ResourceLimits limits;
};

/// A grid of equal rectangular blocks (a `blocks` entry with a `grid`).
struct BlockGrid
{
  Point origin = Point::Zero();              ///< lower-left corner [m]
  Point cell_size = Point::Zero();           ///< [width, height] of each rectangle [m]
  std::array<std::size_t, 2> count = {0, 0}; ///< [nx, ny]
};

/// What the program chose for a tunnel, and why (printed by `check`).
struct TunnelPlan
{
  TunnelTruncation truncation = TunnelTruncation::hybrid;
  Point near_lower = Point::Zero(), near_upper = Point::Zero();       ///< the blocks' rectangle [m]
  Point opening_lower = Point::Zero(), opening_upper = Point::Zero(); ///< its bounding box [m]
  std::size_t n_blocks = 0;
  double mean_block_size = 0.0; ///< sqrt of the mean block area [m]
  /// E of the near field's boundary blocks with the joints behind them, 1 / (1/E + L/(2 p d))
  /// averaged over the boundary (coupling/README.md): the far field's modulus [Pa].
  double rock_mass_modulus = 0.0;
  double vp = 0.0, vs = 0.0; ///< of the rock mass [m/s] (plane strain)
  double wave_speed = 0.0;   ///< of the incident wave [m/s]
  /// A deal.II far field (hybrid, reference); the extents below also bound the outer blocks.
  bool far_field = false;
  /// The model's outer rectangle [m]: the far field's (hybrid, reference) or the outer blocks'
  /// (blocks); zero for vb1 and dashpot.
  Point far_lower = Point::Zero(), far_upper = Point::Zero();
  double margin = 0.0;                  ///< beyond the near field [m]
  double side_margin = 0.0;             ///< beside it [m]: margin, wider for blocks
  double far_element_size = 0.0;        ///< [m], FE_Q2
  double near_element_size = 0.0;       ///< at the near field [m]
  double elements_per_wavelength = 0.0; ///< far elements per S wavelength at max_frequency
  /// blocks: the ring from the near field to far_lower/far_upper as 8 grids (the 3 x 3 tensor
  /// grid of the margins and the near field, without its centre); the outer blocks come before
  /// the near field's in the scene's block list.
  std::vector<BlockGrid> outer_grids;
  std::size_t n_outer_blocks = 0;
  double outer_block_size = 0.0;      ///< target side: shortest S wavelength / points [m]
  double outer_youngs_modulus = 0.0;  ///< E_o of the outer blocks [Pa]
  double outer_joint_stiffness = 0.0; ///< normal spring p of their bonded joints [N/m]
  double outer_shear_ratio = 0.0;     ///< shear spring / p of their bonded joints [-]
  double outer_strength = 0.0;        ///< cohesion and tensile strength of their joints [Pa]
  bool top_is_surface = false;        ///< the model reaches the ground surface (traction free)
  double surface_y = 0.0;             ///< [m]
  double arrival_time = 0.0;          ///< the incident wave reaches the near field's base [s]
  double end_time = 0.0;              ///< [s]
  double dt = 0.0;                    ///< [s]
  double static_dt = 0.0;             ///< pseudo time step of the static stage [s]
  /// The settle stage (none if not TunnelDescription::settle).
  std::optional<dda::SettleCriterion> settle;
  std::vector<std::string> reasons; ///< one line per choice, for `check`
};

/// Young's modulus E_o [Pa] of square blocks that, bonded to their neighbours by two springs
/// `normal_stiffness` p [N/m] per shared edge, make a grid of modulus `grid_modulus` E_grid
/// [Pa]: jointed_block_modulus(E_o, p, s^2, s) = E_grid for any side s, i.e.
/// E_o = 1 / (1 / E_grid - 1 / (2 p)) (p per metre out of the plane, in Pa). Throws InputError
/// if 2 p <= E_grid: the springs alone are softer than the grid must be.
double outer_block_modulus(double grid_modulus, double normal_stiffness);

/// Chooses the near field, far field, time step and duration. Generates the blocks once to
/// measure them. Throws InputError (without a location; the caller adds it) when the tunnel
/// does not fit (e.g. a near field reaching above the ground surface).
TunnelPlan plan_tunnel(const TunnelDescription& tunnel);

} // namespace ddafem
