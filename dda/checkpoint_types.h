// How the blocks' plain types are stored in a checkpoint (Boost.Serialization's free
// `serialize`, found by argument-dependent lookup), and Eigen's dense matrices. Only the
// checkpoint files include this.
#pragma once

#include "common/checkpoint_archive.h"
#include "dda/joints.h"
#include "dda/system.h"

#include <Eigen/Core>

#include <cstdint>
#include <tuple>

namespace boost::serialization
{
/// Eigen's dense matrices and vectors: the size, then the coefficients as bytes.
template <class Archive, typename Scalar, int Rows, int Cols, int Options, int MaxRows, int MaxCols>
void serialize(Archive& archive, Eigen::Matrix<Scalar, Rows, Cols, Options, MaxRows, MaxCols>& m,
               const unsigned int /*version*/)
{
  std::int64_t rows = m.rows(), cols = m.cols();
  ddafem::transfer_all(archive, rows, cols);
  if constexpr (Archive::is_loading::value)
    m.resize(rows, cols);
  auto values = make_array(m.data(), static_cast<std::size_t>(m.size()));
  ddafem::transfer_all(archive, values);
}
/// Tuples (contact keys): their elements in order.
template <class Archive, typename... T>
void serialize(Archive& archive, std::tuple<T...>& t, const unsigned int /*version*/)
{
  std::apply([&archive](auto&... element) { ((archive & element), ...); }, t);
}
} // namespace boost::serialization

namespace ddafem::dda
{
template <class Archive>
void serialize(Archive& a, PolygonMoments& m, const unsigned int /*version*/)
{
  transfer_all(a, m.area, m.centroid, m.sxx, m.syy, m.sxy);
}

template <class Archive>
void serialize(Archive& a, MaterialPoint& p, const unsigned int /*version*/)
{
  transfer_all(a, p.block, p.position, p.initial);
}

template <class Archive>
void serialize(Archive& a, ContactForces& f, const unsigned int /*version*/)
{
  transfer_all(a, f.state, f.normal_force, f.shear_force, f.intact);
}

template <class Archive>
void serialize(Archive& a, Contact& c, const unsigned int /*version*/)
{
  transfer_all(a, c.id, c.vertex_block, c.vertex, c.edge_block, c.edge, c.kind, c.joint_material);
  transfer_all(a, c.length, c.ratio, c.gap, c.forces, c.trial, c.end_gap, c.step_slip,
               c.total_slip);
  transfer_all(a, c.slide_duration, c.penalty_factor, c.coupling);
}

template <class Archive>
void serialize(Archive& a, JointPoint& p, const unsigned int /*version*/)
{
  transfer_all(a, p.on_a, p.on_b, p.normal_force, p.shear_force, p.normal_preload, p.shear_preload);
}

template <class Archive>
void serialize(Archive& a, Joint& j, const unsigned int /*version*/)
{
  transfer_all(a, j.id, j.block_a, j.block_b, j.joint_material, j.edge_a, j.edge_b, j.coupling);
  transfer_all(a, j.length, j.points);
}

template <class Archive>
void serialize(Archive& a, BoundaryStep& s, const unsigned int /*version*/)
{
  transfer_all(a, s.k, s.f);
}

template <class Archive>
void serialize(Archive& a, BlockBalance& b, const unsigned int /*version*/)
{
  transfer_all(a, b.out_of_balance, b.load, b.weight);
}

template <class Archive>
void serialize(Archive& a, IntegratorCoefficients& c, const unsigned int /*version*/)
{
  transfer_all(a, c.beta, c.gamma, c.alpha_m, c.alpha_f);
}

template <class Archive>
void serialize(Archive& a, PhaseTimings& t, const unsigned int /*version*/)
{
  transfer_all(a, t.broad_phase, t.narrow_phase, t.assemble, t.solve, t.update, t.tie_terms);
  transfer_all(a, t.tied_body, t.n_steps, t.n_attempts, t.n_open_close_iterations);
}

template <class Archive>
void serialize(Archive& a, SolveStatus& s, const unsigned int /*version*/)
{
  transfer_all(a, s.success, s.factorized, s.n_refinements, s.relative_residual, s.message);
}

template <class Archive>
void serialize(Archive& a, StepStatus& s, const unsigned int /*version*/)
{
  transfer_all(a, s.outcome, s.message, s.solve, s.n_open_close_iterations, s.n_state_changes);
  transfer_all(a, s.max_displacement, s.max_penetration, s.penalty_raised, s.n_flips_ignored);
  transfer_all(a, s.unbalanced_force_ratio, s.unbalanced_block, s.reversal_fraction);
}

} // namespace ddafem::dda
