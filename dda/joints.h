// Joints between blocks that share an edge (issue 2: bonded joints).
#pragma once

#include "dda/block.h"
#include "dda/contact/contact_law.h"
#include "dda/model_description.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace ddafem::dda
{
/// One end of a joint: the same point attached to both blocks, joined by a normal spring p and a
/// shear spring p * shear_ratio (Shi's edge-to-edge contact as two vertex springs).
struct JointPoint
{
  MaterialPoint on_a;        ///< the point as part of block a
  MaterialPoint on_b;        ///< the point as part of block b
  double normal_force = 0.0; ///< spring force [N], tension positive (blocks pulled together)
  double shear_force = 0.0;  ///< spring force [N] along the joint tangent t (see Joint::tangent)
  /// Preload [N] (the in-situ stress's traction across the joint times the end's half length),
  /// tension positive and along t like the forces: the spring's force is the preload plus the
  /// springs on the gap, i.e. it starts stretched by preload / stiffness.
  double normal_preload = 0.0;
  double shear_preload = 0.0;
};

/// A bonded joint along the shared stretch of an edge of block a and an edge of block b.
struct Joint
{
  std::size_t id = 0;      ///< stable over the run
  std::size_t block_a = 0; ///< block_a < block_b
  std::size_t block_b = 0;
  std::size_t joint_material = 0;
  std::size_t edge_a = 0;           ///< edge of block a it lies on (vertex edge_a to edge_a + 1)
  std::size_t edge_b = 0;           ///< edge of block b it lies on
  std::size_t coupling = 0;         ///< index of the (a, b) coupling block in the system matrix
  double length = 0.0;              ///< initial length of the shared stretch [m]
  std::array<JointPoint, 2> points; ///< its two ends, in a's edge direction

  /// Unit tangent along a's edge (a's anticlockwise direction), at the current positions or, with
  /// `initial`, at t = 0.
  Vector2 tangent(bool initial = false) const;
  /// Unit normal pointing out of block a, towards b: (t_y, -t_x).
  Vector2 normal(bool initial = false) const;
  /// The unit normal of a unit tangent t: (t_y, -t_x) (normal() of a tangent already at hand).
  static Vector2 normal_of(const Vector2& tangent) { return Vector2(tangent.y(), -tangent.x()); }
};

/// The springs of a bonded joint's end: p n n^T + p_s t t^T [N/m], with p the joint material's
/// normal stiffness, p_s = shear_ratio p, n the joint's unit normal (out of block a) and t its
/// unit tangent (Joint::normal, Joint::tangent).
Eigen::Matrix2d joint_spring_matrix(const JointMaterial& jm, const Vector2& n, const Vector2& t);

/// Sets the forces of a joint end's springs at its gap g = x_b - x_a [m] (the point on b minus
/// the point on a): N = N0 + p n.g and S = S0 + p_s t.g [N], tension positive, with N0 and S0
/// the preloads.
void update_joint_point_forces(JointPoint& p, const JointMaterial& jm, const Vector2& n,
                               const Vector2& t);

/// Energy stored in a joint end's springs [J]: N^2 / (2 p) + S^2 / (2 p_s).
double joint_point_energy(const JointPoint& p, const JointMaterial& jm);

/// The contact law of a joint end's springs: the joint material's p and p_s, tan(phi)
/// `tan_friction`, and its cohesion and tensile strength [Pa] over the length the end carries,
/// `length` [m] (half the joint's), as cohesive force and tensile capacity [N]. Its strength
/// decides when the joint breaks (exceeds_strength).
ContactLaw joint_point_law(const JointMaterial& jm, double tan_friction, double length);

/// Joint material between blocks of two materials: a matching `joint_assignments` entry, else
/// the default (npos if there is none).
std::size_t joint_material_for(const ModelDescription& model, std::size_t material_a,
                               std::size_t material_b);

/// Joint material of a joint or contact along edge `edge` of block `block` (index into
/// model.blocks) against block `other`: the edge's own (BlockDescription::edge_joint_materials),
/// else joint_material_for the two blocks' materials (npos if there is none).
std::size_t joint_material_at_edge(const ModelDescription& model, std::size_t block,
                                   std::size_t edge, std::size_t other);

/// The in-situ traction sigma0 n, linear along a straight edge from x0 to x1 (length l [m]),
/// as the two end forces [N] that give its exact generalised force for the linear T along the
/// edge: l/6 (2 t0 + t1) and l/6 (t0 + 2 t1) (each end's half, l/2 t, would miss the moment of
/// a stress gradient along the edge on the shear-strain unknown).
std::array<Vector2, 2> in_situ_end_forces(const InSituStress& in_situ, const Point& x0,
                                          const Point& x1, const Vector2& n, double l);

/// Finds every pair of blocks that share an edge stretch and makes a bonded joint there, with the
/// joint material of the shared edges (joint_material_at_edge; where both edges have their own
/// and they differ, the shorter edge's, which the shared stretch covers more of), else the one
/// assigned to the pair's materials. Blocks are paired by a sweep over their
/// bounding boxes (not all pairs). Throws InputError (naming the blocks) where two blocks share
/// an edge and no joint material applies. `tol` [m] is the collinearity tolerance.
std::vector<Joint> find_joints(const std::vector<Block>& blocks, const ModelDescription& model,
                               const std::vector<std::string>& block_names, double tol);

} // namespace ddafem::dda
