// Viscous (absorbing) boundaries on DDA block edges: VB I (Bao, Hatzor & Huang 2012, eq. 39),
// VB II (Jiao et al. 2007, eq. 40) and the consistent dashpot (docs/reference/physics.md section
// 3).
#pragma once

#include "dda/block.h"
#include "dda/joints.h"
#include "dda/model_description.h"

#include <Eigen/Core>

#include <cstddef>
#include <limits>
#include <vector>

namespace ddafem::dda
{
/// VB I's factor D(x) = 2 / (1 + exp(-x)) of eq. 37, with x = c dt / m.
double vb1_factor(double x);

/// VB I acts as a dashpot of coefficient c (D(x) - x) on the step's mean velocity: its stiffness
/// per component is (c / dt) (D(x) - x). This is the root x0 = 1.6879 of D(x) = x: below it VB I
/// absorbs energy (the less, the closer x is to x0); at x0 it is a free edge; above it the
/// stiffness is negative and the boundary feeds energy into the model. The paper's eq. 44
/// (x < 1) and its warning at x = 2 (with ct) bracket this value.
double vb1_source_threshold();

/// Wave speeds [m/s] that set a boundary edge's dashpots.
struct BoundaryWaveSpeeds
{
  double p = 0.0;
  double s = 0.0;
};

/// Textbook speeds of a material: VP = sqrt(E (1-nu) / (rho (1+nu)(1-2nu))), VS = sqrt(G / rho).
BoundaryWaveSpeeds textbook_wave_speeds(const Material& material);

/// One block edge of a boundary with its dashpots.
struct BoundaryEdge
{
  std::size_t boundary = 0; ///< index into ModelDescription::boundaries
  std::size_t block = 0;
  std::size_t edge = 0;   ///< from vertex `edge` to `edge + 1` (anticlockwise: domain on the left)
  MaterialPoint midpoint; ///< where T is evaluated
  double length = 0.0;    ///< l0 [m]
  BoundaryWaveSpeeds speeds;    ///< the speeds used for cn and ct
  BoundaryWaveSpeeds textbook;  ///< for reports
  BoundaryWaveSpeeds effective; ///< for reports
  double cn = 0.0;              ///< a_n rho l0 VP [N s/m]
  double ct = 0.0;              ///< a_t rho l0 VS [N s/m]
};

/// Finds the edges a boundary applies to and sets their coefficients. Outer edges are those no
/// joint lies on. Throws InputError naming the boundary if it selects no edge, or an explicit
/// edge that does not exist or is shared by a joint.
std::vector<BoundaryEdge> select_boundary_edges(std::size_t boundary_index,
                                                const ModelDescription& model,
                                                const std::vector<Block>& blocks,
                                                const std::vector<Joint>& joints, double tol);

/// The effective speeds across a boundary edge: the block's P modulus (E for a plane-stress
/// block whose side edges are free, i.e. a one-block bar; E / (1 - nu^2) in plane stress
/// otherwise; lambda + 2 mu in plane strain) and its shear modulus G, each in series with the
/// joint behind it (the joint parallel to the edge: two springs p, p_s over its length L_j give
/// 2 p / L_j per unit area) over the block's depth h along the normal:
/// M_eff = 1 / (1 / M + 1 / (h 2 p / L_j)).
BoundaryWaveSpeeds effective_wave_speeds(const ModelDescription& model,
                                         const std::vector<Block>& blocks,
                                         const std::vector<Joint>& joints, std::size_t block,
                                         std::size_t edge, double tol);

/// Stability of one boundary edge at time step dt.
struct BoundaryStability
{
  double mass = 0.0; ///< of the boundary block [kg]
  double x_n = 0.0;  ///< cn dt / m
  double x_t = 0.0;  ///< ct dt / m
  /// Largest dt at which the edge still absorbs energy: for VB I the dt where max(x_n, x_t)
  /// reaches vb1_source_threshold(); beyond it the edge is an energy source. Infinite for the
  /// unconditionally dissipative VB II and dashpot, and for free edges.
  double dt_source = std::numeric_limits<double>::infinity();
  double dt_paper_bound = std::numeric_limits<double>::infinity();  ///< eq. 44: m / cn (VB I)
  double dt_paper_source = std::numeric_limits<double>::infinity(); ///< 2 m / ct (VB I)
  bool is_source = false;                                           ///< dt > dt_source
};

BoundaryStability boundary_stability(BoundaryType type, const BoundaryEdge& edge, double mass,
                                     double dt);

/// The 2x2 stiffness [N/m] and force [N] a boundary adds at its edge midpoint in one step, in
/// global (x, y) components: the step equation gains T^T k T on the block's diagonal and T^T f
/// on its right-hand side. `normal` is the outward unit normal; `velocity0`, `acceleration0` are
/// the midpoint's at the step's start; (beta, gamma) the Newmark parameters; `mass` the block's.
struct BoundaryStep
{
  Eigen::Matrix2d k = Eigen::Matrix2d::Zero();
  Vector2 f = Vector2::Zero();
};
BoundaryStep boundary_step(BoundaryType type, const BoundaryEdge& edge, const Vector2& normal,
                           double mass, double dt, double beta, double gamma,
                           const Vector2& velocity0, const Vector2& acceleration0);

} // namespace ddafem::dda
