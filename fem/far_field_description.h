// Input of a deal.II far-field model (plain data, validated by the scene reader).
#pragma once

#include "common/elasticity.h"
#include "common/enum_names.h"
#include "common/time_function.h"
#include "common/wave_type.h"

#include <array>
#include <map>
#include <string>
#include <vector>

namespace ddafem::fem
{
/// 2D idealisation of the continuum (common/elasticity.h); plane strain is the default for a far
/// field around a long tunnel.
using PlaneMode = ddafem::PlaneMode;

/// Time integrator of the far field: both are Newmark schemes (docs/reference/physics.md section
/// 2).
enum class Integrator
{
  newmark_trapezoidal, ///< beta = 1/4, gamma = 1/2: second order, no algorithmic damping
  dda                  ///< beta = 1/2, gamma = 1: DDA's scheme, for like-for-like comparisons
};

constexpr std::array<EnumName<Integrator>, 2> enum_names(Integrator)
{
  return {{{Integrator::dda, "dda"}, {Integrator::newmark_trapezoidal, "newmark_trapezoidal"}}};
}

/// What one named boundary part does.
enum class BoundaryKind
{
  free,   ///< traction free
  fixed,  ///< zero displacement
  lysmer, ///< Lysmer-Kuhlemeyer dashpots: t = -rho (a VP (v.n) n + b VS (v - (v.n) n))
  /// Absorbing base with an incident plane wave (Joyner & Chen 1975, docs/reference/physics.md
  /// section 5): the dashpots above plus the traction rho c (2 v_in) per component.
  input,
  /// Roller: zero displacement along the component the incident wave does not move: u_x = 0
  /// for a P wave (vertical particle motion), u_y = 0 for an SV wave (horizontal particle
  /// motion); the other component is free. On the lateral sides of a column under a vertically
  /// incident wave this is exactly the 1D (free-field) solution: for P it is the usual roller
  /// (zero normal displacement), for SV it holds u_y = 0 and leaves u_x free.
  roller,
  /// Free-field lateral boundary (left or right side; Zienkiewicz et al. 1989, Nielsen 2006):
  /// the Lysmer dashpots act on the motion relative to a 1D column solved alongside (same
  /// material, base and top, rollers), t = sigma_ff n - D (v - v_ff). Exact for a vertically
  /// incident plane wave far from whatever the model holds (a hole), which the plain dashpots
  /// are not: they resist the free-field motion itself.
  free_field
};

constexpr std::array<EnumName<BoundaryKind>, 6> enum_names(BoundaryKind)
{
  return {{{BoundaryKind::free, "free"},
           {BoundaryKind::fixed, "fixed"},
           {BoundaryKind::lysmer, "lysmer"},
           {BoundaryKind::input, "input"},
           {BoundaryKind::roller, "roller"},
           {BoundaryKind::free_field, "free_field"}}};
}

/// Boundary parts of the far field, named as in scenes: the sides of the rectangle and the
/// boundary of the hole (a generated hole, or the part a Gmsh file tags as `hole`).
enum class BoundaryPart
{
  bottom,
  right,
  top,
  left,
  hole
};

constexpr std::array<EnumName<BoundaryPart>, 5> enum_names(BoundaryPart)
{
  return {{{BoundaryPart::bottom, "bottom"},
           {BoundaryPart::right, "right"},
           {BoundaryPart::top, "top"},
           {BoundaryPart::left, "left"},
           {BoundaryPart::hole, "hole"}}};
}

/// fem::name_of(part) as callers spell it: the common name_of of the tables above.
using ddafem::name_of;

/// Springs beside the dashpots of a lysmer part: the viscous-spring artificial boundary of Deeks
/// & Randolph (1994) and Liu et al. (2006), K = G / R (alpha_n n n^T + alpha_t (I - n n^T)) per
/// unit length, R the distance from the wave source `center`. A wave radiating from the centre
/// is cylindrical at the boundary: the dashpots alone absorb its far-field (plane) part and
/// reflect the near-field part, which the springs take up.
struct BoundarySprings
{
  bool enabled = false;
  std::array<double, 2> center{{0.0, 0.0}}; ///< [m]
  double alpha_n = 1.0;                     ///< [-] (Liu et al. 2006, 2D: 0.8 to 1.2)
  double alpha_t = 0.5;                     ///< [-] (0.35 to 0.65)
};

struct BoundaryCondition
{
  BoundaryPart part = BoundaryPart::bottom;
  BoundaryKind kind = BoundaryKind::free;
  double a = 1.0;          ///< Lysmer normal coefficient [-]
  double b = 1.0;          ///< Lysmer tangential coefficient [-]
  BoundarySprings springs; ///< lysmer parts only
};

/// A vertically incident plane wave entering through the `input` part: particle velocity
/// v_in(t) [m/s] of the upgoing wave, horizontal for SV and vertical for P.
struct IncidentWave
{
  using Type = WaveType;
  Type type = Type::sv;
  TimeFunction velocity = TimeFunction::constant(0.0);
};

struct Monitor
{
  std::string name;
  std::array<double, 2> point{{0.0, 0.0}}; ///< [m], inside the domain
};

/// Shape of the hole in a generated far-field mesh (for the DDA near field).
enum class HoleShape
{
  none,
  rectangle, ///< [lower, upper]
  polygon,   ///< vertices, star-shaped about their area centroid
  circle     ///< center, radius (the boundary follows the circle under refinement)
};

constexpr std::array<EnumName<HoleShape>, 3> enum_names(HoleShape)
{
  return {{{HoleShape::rectangle, "rectangle"},
           {HoleShape::polygon, "polygon"},
           {HoleShape::circle, "circle"}}};
}

/// A hole in the rectangle. The mesh is an O-grid of quadrilaterals between the hole and a box
/// about twice its size, a Cartesian grid outside the box, and local refinement (hanging nodes)
/// until every element is at most min(far size, element_size + (growth_ratio - 1) d), d the
/// distance of its centre from the hole.
struct HoleDescription
{
  HoleShape shape = HoleShape::none;
  std::array<double, 2> lower{{0.0, 0.0}};     ///< rectangle [m]
  std::array<double, 2> upper{{0.0, 0.0}};     ///< rectangle [m]
  std::vector<std::array<double, 2>> vertices; ///< polygon [m], either orientation
  std::array<double, 2> center{{0.0, 0.0}};    ///< circle [m]
  double radius = 0.0;                         ///< circle [m]
  double element_size = 0.0;                   ///< element size at the hole [m]; 0: the far size
  double growth_ratio = 1.3; ///< size ratio of neighbouring elements away from the hole, > 1
};

/// A mesh read from a Gmsh file (ASCII msh 2 or 4) instead of the generated rectangle: its
/// physical line tags name the boundary parts; untagged boundary lines are free.
struct MeshFile
{
  std::string file;                           ///< empty: generated mesh
  std::map<BoundaryPart, unsigned int> parts; ///< physical line tag of each named part
};

/// Linear solver of the constant effective matrix.
enum class LinearSolver
{
  direct, ///< sparse LU factorized once, one forward and back substitution per step
  cg      ///< conjugate gradients with a Jacobi preconditioner, warm-started from the predictor
};

constexpr std::array<EnumName<LinearSolver>, 2> enum_names(LinearSolver)
{
  return {{{LinearSolver::direct, "direct"}, {LinearSolver::cg, "cg"}}};
}

/// Implementation of LinearSolver::direct (not a scene key: KLU was faster everywhere measured,
/// bench/fem_bench.py compares them).
enum class DirectSolver
{
  cholmod, ///< SuiteSparse CHOLMOD, supernodal Cholesky (the matrix is SPD)
  klu,     ///< SuiteSparse KLU
  umfpack  ///< deal.II SparseDirectUMFPACK
};

/// How the absorbing (lysmer, input) parts are held while the static stage is solved.
enum class StaticSupport
{
  fixed, ///< both displacement components zero
  roller ///< the normal component zero (x on left/right, y on bottom/top; the hole: both)
};

constexpr std::array<EnumName<StaticSupport>, 2> enum_names(StaticSupport)
{
  return {{{StaticSupport::fixed, "fixed"}, {StaticSupport::roller, "roller"}}};
}

/// A static stage ahead of the dynamic one: gravity and an in-situ stress
/// sigma0(y) = stress + stress_gradient (y - reference_y) solved as K u_s = f_gravity -
/// integral(B^T sigma0) with the absorbing parts supported. The reactions are then kept as
/// constant forces (the dynamic stage applies K u_s) and the dashpots act; the dynamic stage
/// starts from u_s at rest. Monitors and snapshots report displacements relative to u_s and the
/// total stress sigma0 + D B u.
struct StaticStage
{
  bool enabled = false;
  std::array<double, 2> gravity{{0.0, 0.0}};              ///< [m/s^2]
  std::array<double, 3> stress{{0.0, 0.0, 0.0}};          ///< (sxx, syy, sxy) at reference_y [Pa]
  std::array<double, 3> stress_gradient{{0.0, 0.0, 0.0}}; ///< d/dy [Pa/m]
  double reference_y = 0.0;                               ///< [m]
  StaticSupport support = StaticSupport::fixed;
};

/// Rayleigh damping C += alpha M + beta K (damping ratio alpha / (2 omega) + beta omega / 2).
struct RayleighDamping
{
  double alpha = 0.0; ///< [1/s]
  double beta = 0.0;  ///< [s]
};

/// A rectangular far field [x0, x1] x [y0, y1] meshed with square-ish FE_Q elements (optionally
/// with a graded hole), or a Gmsh mesh.
struct FarFieldDescription
{
  std::array<double, 2> lower{{0.0, 0.0}}; ///< (x0, y0) [m]
  std::array<double, 2> upper{{1.0, 1.0}}; ///< (x1, y1) [m]
  /// Element size [m]; 0: chosen from `points_per_wavelength` at `max_frequency` and VS.
  double element_size = 0.0;
  double max_frequency = 0.0;          ///< highest frequency of interest [Hz]
  double points_per_wavelength = 10.0; ///< nodes per shortest S wavelength
  unsigned int degree = 2;             ///< FE_Q degree, 1 or 2
  double density = 0.0;                ///< [kg/m^3]
  double youngs_modulus = 0.0;         ///< [Pa]
  double poisson_ratio = 0.0;          ///< [-]
  PlaneMode plane_mode = PlaneMode::strain;
  std::vector<BoundaryCondition> boundaries; ///< parts not listed are free
  IncidentWave incident;
  std::vector<Monitor> monitors;
  double dt = 0.0;       ///< [s]
  double end_time = 0.0; ///< [s]
  Integrator integrator = Integrator::newmark_trapezoidal;
  HoleDescription hole;
  MeshFile mesh_file;
  LinearSolver solver = LinearSolver::direct;
  DirectSolver direct_solver = DirectSolver::cholmod;
  double solver_tolerance = 1e-12; ///< cg: residual relative to the right-hand side
  StaticStage static_stage;
  RayleighDamping rayleigh;
};

/// zlib level of the far field's VTU files. best_compression (deal.II's default) spends about
/// four times the writing time of best_speed for files 4% smaller (the default tunnel scene:
/// 41 snapshots, 5.3 s against 1.3 s of a 8.3 s run; docs/performance.md, profile).
enum class VtuCompression
{
  none,
  best_speed,
  best_compression
};

constexpr std::array<EnumName<VtuCompression>, 3> enum_names(VtuCompression)
{
  return {{{VtuCompression::best_speed, "best_speed"},
           {VtuCompression::best_compression, "best_compression"},
           {VtuCompression::none, "none"}}};
}

} // namespace ddafem::fem
