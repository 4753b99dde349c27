// The far field's side of the DDA coupling (coupling/far_field_ties.h): point springs from
// far-field points to an outside body, and the step in two halves around the outside body's
// solve. ElasticWaveModel (one process) and DistributedWaveModel (MPI ranks) both offer it.
#pragma once

#include "common/step_result.h"
#include "fem/far_field_description.h"

#include <array>
#include <string>
#include <vector>

namespace ddafem::fem
{
/// A spring between a far-field point and an outside body (the ties of coupling/, issue 6).
struct PointSpring
{
  std::array<double, 2> point{{0.0, 0.0}};               ///< [m], near a boundary part
  std::array<double, 4> stiffness{{0.0, 0.0, 0.0, 0.0}}; ///< K (2 x 2 row-major, symmetric) [N/m]
};

/// Spring k ties the far field's displacement N_k u at the point X_k to an outside body. Over a
/// step the far field solves P u = f + N^T q, P = A + sum N_k^T K_k N_k (A the effective matrix,
/// f the Newmark right-hand side) and q the point loads the caller sets; the springs' force on
/// the far field is then F_k = q_k - K_k N_k u. With q_k = K_k z_k this is a spring to the
/// target displacement z_k. Point vectors are 2m long, (x, y) per spring; matrices 2m x 2m
/// row-major. A distributed far field gives every rank the same numbers, bit for bit.
class PointSpringField
{
public:
  virtual ~PointSpringField() = default;

  /// Ties springs to the boundary faces of `part`, each at the point of the part nearest to the
  /// given point; returns each given point's distance from the part [m] (the caller judges it).
  /// Throws InputError if the part has no faces or the model cannot take springs. Changes the
  /// effective matrix.
  virtual std::vector<double> add_point_springs(BoundaryPart part,
                                                const std::vector<PointSpring>& springs) = 0;
  /// The boundary faces of `part` as straight segments {x0, y0, x1, y1} [m].
  virtual std::vector<std::array<double, 4>> boundary_segments(BoundaryPart part) const = 0;
  /// G = N P^-1 N^T for steps of dt: the displacements [m] at the spring points per unit point
  /// load [N].
  virtual std::vector<double> point_flexibility(double dt) = 0;
  /// First half of a step of dt: assembles f and solves P y = f; returns N y, the spring points'
  /// displacements at the end of the step for q = 0 [m].
  virtual StepResult prepare_step(double dt, std::vector<double>& free_point_displacements) = 0;
  /// Second half: u = y + P^-1 N^T q with the point loads q [N] (2m), then velocities,
  /// accelerations and energies. Only after prepare_step().
  virtual StepResult finish_step(const std::vector<double>& point_loads) = 0;
  /// N u: the far field's displacements at the spring points now [m] (2m; a collective call
  /// across MPI ranks).
  virtual std::vector<double> point_displacements() const = 0;
  /// Work of the springs on the far field since t = 0 [J].
  virtual double work_of_springs() const = 0;
  /// Whether prepare_step may run on a thread other than the caller's (not across MPI ranks).
  virtual bool steps_on_any_thread() const { return true; }
};

} // namespace ddafem::fem
