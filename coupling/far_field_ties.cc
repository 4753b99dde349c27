#include "coupling/far_field_ties.h"

#include "common/format.h"
#include "common/input_error.h"
#include "common/stopwatch.h"

#include <deal.II/base/quadrature_lib.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace ddafem::coupling
{
namespace
{
using Segment = std::array<double, 4>; // x0, y0, x1, y1 [m]

double distance_to_segment(const dda::Point& p, const Segment& s)
{
  const dda::Point a(s[0], s[1]), b(s[2], s[3]);
  const dda::Vector2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

/// The larger side of the blocks' bounding box [m], for tolerances.
double extent_of(const std::vector<dda::Block>& blocks)
{
  dda::Point lo = blocks[0].vertices[0], hi = lo;
  for (const dda::Block& b : blocks)
    for (const dda::Point& v : b.vertices)
    {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
  return (hi - lo).maxCoeff();
}

double distance_to_part(const dda::Point& p, const std::vector<Segment>& segments)
{
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& s : segments)
    best = std::min(best, distance_to_segment(p, s));
  return best;
}

/// Breakpoints of the edge [a, b] at the ends of the part's segments that lie along it: sorted
/// arc lengths from a, 0 and the edge's length included [m].
std::vector<double> breakpoints_along(const dda::Point& a, const dda::Point& b,
                                      const std::vector<Segment>& segments, double tol)
{
  const double length = (b - a).norm();
  const dda::Vector2 t = (b - a) / length;
  const dda::Vector2 n(-t.y(), t.x());
  std::vector<double> breaks = {0.0, length};
  for (const Segment& s : segments)
    for (const dda::Point& p : {dda::Point(s[0], s[1]), dda::Point(s[2], s[3])})
    {
      const double along = t.dot(p - a);
      if (std::abs(n.dot(p - a)) <= tol && along > tol && along < length - tol)
        breaks.push_back(along);
    }
  std::sort(breaks.begin(), breaks.end());
  std::vector<double> unique = {0.0};
  for (const double x : breaks)
    if (x > unique.back() + tol)
      unique.push_back(x);
  unique.back() = length;
  return unique;
}

/// out = D x with D block diagonal (2 x 2 per tie).
Eigen::VectorXd block_diagonal_times(const std::vector<Eigen::Matrix2d>& d,
                                     const Eigen::VectorXd& x)
{
  Eigen::VectorXd out(x.size());
  for (std::size_t k = 0; k < d.size(); ++k)
    out.segment<2>(2 * k) = d[k] * x.segment<2>(2 * k);
  return out;
}

/// D A D for D block diagonal, A dense and symmetric.
Eigen::MatrixXd congruence(const std::vector<Eigen::Matrix2d>& d, const Eigen::MatrixXd& a)
{
  const auto n = a.rows();
  Eigen::MatrixXd left(n, n), out(n, n);
  for (std::size_t k = 0; k < d.size(); ++k)
    left.middleRows<2>(2 * k) = d[k] * a.middleRows<2>(2 * k);
  for (std::size_t k = 0; k < d.size(); ++k)
    out.middleCols<2>(2 * k) = left.middleCols<2>(2 * k) * d[k].transpose();
  return out;
}
} // namespace

FarFieldTies::FarFieldTies(dda::System& system, fem::PointSpringField& far_field_,
                           const InterfaceDescription& d)
    : far_field(far_field_)
{
  const std::string part = fem::name_of(d.part);
  const std::vector<Segment> segments = far_field.boundary_segments(d.part);
  if (segments.empty())
    throw InputError("interface: the far field has no boundary part '" + part +
                     "': expected the part the blocks fill");
  for (const Segment& s : segments)
    length_of_part += std::hypot(s[2] - s[0], s[3] - s[1]);
  if (!(d.normal_stiffness > 0.0))
    throw InputError("interface: normal_stiffness = " + format_number(d.normal_stiffness) +
                     ", expected > 0 [N/m]");

  const std::vector<dda::Block>& blocks = system.blocks().list;
  const double tol = d.tolerance > 0.0 ? d.tolerance : 1e-6 * extent_of(blocks);
  linear = std::isinf(d.cohesion) && std::isinf(d.tensile_strength);
  std::vector<fem::PointSpring> springs;
  std::vector<dda::MaterialPoint> points;
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    const std::vector<dda::Point>& v = blocks[i].vertices; // anticlockwise
    for (std::size_t e = 0; e < v.size(); ++e)
    {
      const dda::Point& a = v[e];
      const dda::Point& b = v[(e + 1) % v.size()];
      if (!(distance_to_part(a, segments) > tol || distance_to_part(b, segments) > tol ||
            distance_to_part(0.5 * (a + b), segments) > tol))
        tie_edge(i, a, b, segments, d, tol, springs, points);
    }
  }
  if (std::abs(length_tied - length_of_part) > 1e-3 * length_of_part)
    throw InputError("interface: the far field's part '" + part + "' is " +
                     format_number(length_of_part) + " m long, but the block edges on it (within " +
                     format_number(tol) + " m) measure " + format_number(length_tied) +
                     " m: expected the blocks to fill the part exactly (" +
                     std::to_string(tied_edges) + " edges found)");

  const std::vector<double> distances = far_field.add_point_springs(d.part, springs);
  for (std::size_t k = 0; k < distances.size(); ++k)
    if (distances[k] > tol)
      throw InputError("interface: tie point (" + format_number(ties[k].point.x()) + ", " +
                       format_number(ties[k].point.y()) + ") of block " +
                       std::to_string(ties[k].block) + " lies " + format_number(distances[k]) +
                       " m from the far field's part '" + part + "', expected within " +
                       format_number(tol) + " m");
  set_bonded_state(system.get_model(), springs);
  h = &k_bonded;
  m_matrix = &m_trial;
  system.tie(*this, points);
}

void FarFieldTies::tie_edge(std::size_t block, const dda::Point& a, const dda::Point& b,
                            const std::vector<Segment>& segments, const InterfaceDescription& d,
                            double tolerance, std::vector<fem::PointSpring>& springs,
                            std::vector<dda::MaterialPoint>& points)
{
  ++tied_edges;
  const double length = (b - a).norm();
  length_tied += length;
  const dda::Vector2 t = (b - a) / length;
  const dda::Vector2 n(t.y(), -t.x()); // out of an anticlockwise block
  const double tan_phi = std::tan(d.friction_angle * M_PI / 180.0);
  // Composite Gauss quadrature over the pieces of the edge between far-field face ends: the
  // tie energy of a linear block edge against a degree-2 face is integrated exactly.
  const std::vector<double> breaks = breakpoints_along(a, b, segments, tolerance);
  const dealii::QGauss<1> gauss(d.points_per_face);
  for (std::size_t piece = 0; piece + 1 < breaks.size(); ++piece)
    for (unsigned q = 0; q < gauss.size(); ++q)
    {
      const double xi =
          (breaks[piece] + gauss.point(q)[0] * (breaks[piece + 1] - breaks[piece])) / length;
      const double weight = gauss.weight(q) * (breaks[piece + 1] - breaks[piece]) / length;
      Tie tie;
      tie.block = block;
      tie.point = a + xi * (b - a);
      tie.normal = n;
      tie.tangent = t;
      tie.length = weight * length;
      tie.law.normal_stiffness = 2.0 * d.normal_stiffness * weight;
      tie.law.shear_stiffness = d.shear_ratio * tie.law.normal_stiffness;
      tie.law.tan_friction = tan_phi;
      tie.law.cohesive_force = d.cohesion * tie.length;
      tie.law.tensile_capacity = d.tensile_strength * tie.length;
      tie.forces.state = dda::ContactState::lock;
      tie.forces.intact = true;
      tie.trial = tie.forces;
      const Eigen::Matrix2d k = tie.law.normal_stiffness * n * n.transpose() +
                                tie.law.shear_stiffness * t * t.transpose();
      springs.push_back({{tie.point.x(), tie.point.y()}, {k(0, 0), k(0, 1), k(1, 0), k(1, 1)}});
      points.push_back({block, tie.point, tie.point});
      ties.push_back(tie);
    }
}

void FarFieldTies::set_bonded_state(const dda::ModelDescription& model,
                                    const std::vector<fem::PointSpring>& springs)
{
  const auto n = static_cast<Eigen::Index>(2 * ties.size());
  k_bonded = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t k = 0; k < ties.size(); ++k)
    k_bonded.block<2, 2>(2 * k, 2 * k) << springs[k].stiffness[0], springs[k].stiffness[1],
        springs[k].stiffness[2], springs[k].stiffness[3];
  previous_force = Eigen::VectorXd::Zero(n);
  preload = Eigen::VectorXd::Zero(n);
  for (std::size_t k = 0; k < ties.size(); ++k)
    preload.segment<2>(2 * k) =
        model.in_situ_stress.traction(ties[k].point, ties[k].normal) * ties[k].length;
  if (!linear && !preload.isZero(0.0))
    throw InputError("interface: a frictional interface cannot carry the in-situ stress's "
                     "preloads (Mohr-Coulomb would see only the dynamic increment): expected no "
                     "`interface.joint_material` with `in_situ_stress`");
}

std::size_t FarFieldTies::n_tied_blocks() const
{
  std::vector<std::size_t> blocks;
  for (const Tie& t : ties)
    blocks.push_back(t.block);
  std::sort(blocks.begin(), blocks.end());
  return static_cast<std::size_t>(std::unique(blocks.begin(), blocks.end()) - blocks.begin());
}

void FarFieldTies::begin_stage(const dda::StageMode mode)
{
  if (mode == dda::StageMode::static_equilibrium)
  {
    if (dynamic_started)
      throw InputError("interface: a static stage after a dynamic one: the far field carries "
                       "the dynamic increment and cannot be held again");
    if (!linear)
      throw InputError("interface: a static stage holds the ties as springs to fixed ground "
                       "and does not follow a frictional interface: expected no "
                       "`interface.joint_material`");
    held = true;
    chain.valid = false;
    h = &k_bonded; // H = K for the whole stage
    bonded_terms_valid = false;
    return;
  }
  if (!held)
    return;
  // Each tie's whole force on its block, P - K z at the equilibrium, becomes its preload; the
  // tie displacements restart at 0 (System::begin_stage) with the far field at rest, and the
  // interface's books start again.
  held = false;
  chain.valid = false; // the tie displacements restart at 0
  for (std::size_t k = 0; k < ties.size(); ++k)
  {
    Tie& t = ties[k];
    preload.segment<2>(2 * k) -= k_bonded.block<2, 2>(2 * k, 2 * k) * t.stretch;
    t.stretch.setZero();
    t.forces.normal_force = t.forces.shear_force = 0.0; // the springs' part starts again
    t.trial = t.forces;
  }
  previous_force.setZero();
  work_blocks = work_preloads = 0.0;
}

Eigen::VectorXd FarFieldTies::bonded_springs(const Eigen::VectorXd& x) const
{
  Eigen::VectorXd f(x.size());
  for (std::size_t k = 0; k < ties.size(); ++k)
    f.segment<2>(2 * k) = k_bonded.block<2, 2>(2 * k, 2 * k) * x.segment<2>(2 * k);
  return f;
}

StepResult FarFieldTies::begin_step(const double dt, const Eigen::VectorXd& displacements)
{
  if (held)
  {
    // The far field held: H = K, g = P - K c; nothing of the far field is solved.
    const auto t0 = Clock::now();
    start = displacements;
    g = preload - bonded_springs(start);
    time_ties += seconds_since(t0);
    return {};
  }
  dynamic_started = true;
  select_condensation(dt);
  std::vector<double> free;
  const StepResult status = far_field.prepare_step(dt, free);
  if (!status.taken)
    return status;
  const auto t0 = Clock::now();
  step_dt = dt;
  w0 = Eigen::Map<const Eigen::VectorXd>(free.data(), static_cast<Eigen::Index>(free.size()));
  start = displacements;
  for (Tie& t : ties)
    t.trial = t.forces;
  build_terms();
  time_ties += seconds_since(t0);
  return {};
}

std::optional<std::uint64_t> FarFieldTies::stiffness_id() const
{
  if (held || !bonded_terms_valid || condensations.empty())
    return std::nullopt;
  std::uint64_t bits = 0;
  const double dt = condensations.front_key();
  std::memcpy(&bits, &dt, sizeof bits);
  return bits;
}

void FarFieldTies::select_condensation(const double dt)
{
  if (!condensations.empty() && condensations.front_key() == dt)
    return;
  bonded_terms_valid = false;
  if (condensations.use(dt) != nullptr)
    return;
  const auto t0 = Clock::now();
  const auto n = static_cast<Eigen::Index>(2 * ties.size());
  const std::vector<double> values = far_field.point_flexibility(dt);
  const Eigen::MatrixXd gm =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          values.data(), n, n);
  auto c = std::make_unique<Condensation>();
  c->flexibility = 0.5 * (gm + gm.transpose()); // symmetric up to the solver's round-off
  condensations.insert(dt, std::move(c));
  ++condensation_count;
  time_condensation += seconds_since(t0);
}

void FarFieldTies::build_terms()
{
  const std::size_t m = ties.size();
  std::vector<Eigen::Matrix2d> k_ties(m), dk(m);
  f_trial = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(2 * m));
  bool all_bonded = true;
  for (std::size_t k = 0; k < m; ++k)
  {
    const Tie& t = ties[k];
    const Eigen::Matrix2d nn = t.normal * t.normal.transpose();
    const Eigen::Matrix2d tt = t.tangent * t.tangent.transpose();
    const double previous_shear =
        t.forces.state != dda::ContactState::open ? t.forces.shear_force : 0.0;
    switch (t.trial.state)
    {
    case dda::ContactState::lock:
      // S = S0 + p_s t.(r - r0): spring on the whole stretch plus a constant.
      k_ties[k] = t.law.normal_stiffness * nn + t.law.shear_stiffness * tt;
      f_trial.segment<2>(2 * k) =
          (previous_shear - t.law.shear_stiffness * t.tangent.dot(t.stretch)) * t.tangent;
      break;
    case dda::ContactState::slide:
      k_ties[k] = t.law.normal_stiffness * nn;
      f_trial.segment<2>(2 * k) = t.trial.shear_force * t.tangent;
      break;
    case dda::ContactState::open:
      k_ties[k].setZero();
      break;
    }
    dk[k] = k_ties[k] - k_bonded.block<2, 2>(2 * k, 2 * k);
    all_bonded = all_bonded && dk[k].isZero(0.0);
  }
  k_trial.resize(static_cast<Eigen::Index>(2 * m), 2);
  for (std::size_t k = 0; k < m; ++k)
    k_trial.middleRows<2>(2 * k) = k_ties[k];

  if (all_bonded)
  {
    if (!bonded_terms_valid)
    {
      Condensation& c = condensations.front();
      if (c.bonded_h.size() == 0)
        c.bonded_h = k_bonded - congruence(k_ties, c.flexibility);
      m_matrix = &c.flexibility;
      h = &c.bonded_h;
      bonded_terms_valid = true;
    }
    r_w0 = w0;
  }
  else
  {
    // R = (I + G dK)^-1: one dense LU of 2m x 2m.
    const auto n = static_cast<Eigen::Index>(2 * m);
    Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n);
    for (std::size_t k = 0; k < m; ++k)
      a.middleCols<2>(2 * k) += flexibility().middleCols<2>(2 * k) * dk[k];
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(a);
    r_w0 = lu.solve(w0);
    m_trial = lu.solve(flexibility());
    m_trial = 0.5 * (m_trial + m_trial.transpose()).eval();
    h_trial = -congruence(k_ties, m_trial);
    for (std::size_t k = 0; k < m; ++k)
      h_trial.block<2, 2>(2 * k, 2 * k) += k_ties[k];
    m_matrix = &m_trial;
    h = &h_trial;
    bonded_terms_valid = false;
  }
  // f on the blocks = P - (K' (z - w) + F0) = g - H delta, z = c + delta. A linear interface's
  // ties are bonded springs, F0 = 0.
  if (linear)
    f_trial.setZero();
  const Eigen::VectorXd w_f = linear ? r_w0 : Eigen::VectorXd(r_w0 + *m_matrix * f_trial);
  g = preload + block_diagonal_times(k_ties, w_f) - f_trial - h_times_start();
}

Eigen::VectorXd FarFieldTies::h_times_start()
{
  // On the chain the step starts where the last one ended (its z: the System's displacements
  // of the tie points differ from it by round-off) and H z0 = K (z0 - G K z0).
  if (!(bonded_step() && chain.valid && chain.dt == step_dt))
    return *h * start;
  start = chain.z;
  return bonded_springs(chain.z - chain.g_k_z);
}

Eigen::VectorXd FarFieldTies::far_field_displacements(const Eigen::VectorXd& z) const
{
  Eigen::VectorXd kz(z.size());
  for (std::size_t k = 0; k < ties.size(); ++k)
    kz.segment<2>(2 * k) = k_trial.middleRows<2>(2 * k) * z.segment<2>(2 * k);
  return r_w0 + *m_matrix * (kz + f_trial);
}

std::size_t FarFieldTies::update_trial_states(const Eigen::VectorXd& delta,
                                              const unsigned iteration, const double negligible,
                                              std::size_t& n_ignored)
{
  if (linear || held)
    return 0;
  const auto t0 = Clock::now();
  const Eigen::VectorXd z = start + delta;
  const Eigen::VectorXd r = z - far_field_displacements(z);
  std::size_t n_changes = 0;
  bool any_change = false;
  for (std::size_t k = 0; k < ties.size(); ++k)
  {
    Tie& t = ties[k];
    const dda::Vector2 rk = r.segment<2>(2 * k);
    // The block point is the contact's vertex, the far field its edge: the gap is the
    // separation along the far field's outward normal -n.
    const dda::ContactForces next =
        dda::evaluate_contact(t.law, t.forces, -t.normal.dot(rk), t.tangent.dot(rk - t.stretch));
    if (dda::state_changed(t.trial, next))
    {
      any_change = true;
      if (dda::change_holds_iteration(iteration, t.trial, next, negligible))
        ++n_changes;
      else
        ++n_ignored;
    }
    t.trial = next;
  }
  if (any_change)
    build_terms();
  time_ties += seconds_since(t0);
  return n_changes;
}

StepResult FarFieldTies::end_step(const Eigen::VectorXd& delta)
{
  auto t0 = Clock::now();
  const Eigen::VectorXd z = start + delta;
  // The preloads' work on the blocks (constant forces), part of the ties' work on them.
  work_preloads += preload.dot(delta);
  work_blocks += preload.dot(delta);
  if (held)
  {
    // Springs to fixed ground: F = K z on the "far field", P - F on the blocks.
    const Eigen::VectorXd f = bonded_springs(z);
    work_blocks -= 0.5 * (previous_force + f).dot(delta);
    previous_force = f;
    for (std::size_t k = 0; k < ties.size(); ++k)
      set_accepted_forces(k, z.segment<2>(2 * k), f.segment<2>(2 * k));
    time_ties += seconds_since(t0);
    return {};
  }
  if (bonded_step())
    return end_bonded_step(z, delta);
  chain.valid = false;
  const Eigen::VectorXd w = far_field_displacements(z);
  Eigen::VectorXd q(z.size()), f(z.size());
  for (std::size_t k = 0; k < ties.size(); ++k)
  {
    const Eigen::Matrix2d kt = k_trial.middleRows<2>(2 * k);
    const Eigen::Matrix2d dk = kt - k_bonded.block<2, 2>(2 * k, 2 * k);
    const Eigen::Vector2d zk = z.segment<2>(2 * k), wk = w.segment<2>(2 * k);
    // P u = f + N^T q with the ties' force F = K' (z - w) + F0 and P holding K.
    q.segment<2>(2 * k) = kt * zk + f_trial.segment<2>(2 * k) - dk * wk;
    f.segment<2>(2 * k) = kt * (zk - wk) + f_trial.segment<2>(2 * k);
  }
  time_ties += seconds_since(t0);
  const StepResult status =
      far_field.finish_step(std::vector<double>(q.data(), q.data() + q.size()));
  if (!status.taken)
    return status;
  t0 = Clock::now();
  work_blocks -= 0.5 * (previous_force + f).dot(delta);
  previous_force = f;
  for (std::size_t k = 0; k < ties.size(); ++k)
    set_accepted_forces(k, z.segment<2>(2 * k) - w.segment<2>(2 * k), f.segment<2>(2 * k));
  time_ties += seconds_since(t0);
  return {};
}

StepResult FarFieldTies::end_bonded_step(const Eigen::VectorXd& z, const Eigen::VectorXd& delta)
{
  // Every tie bonded: P u = f + N^T q with q = K z (P holds K), and the ties' force on the far
  // field F = K (z - w) with w = N u, the far field's displacements at the ties.
  auto t0 = Clock::now();
  const Eigen::VectorXd q = bonded_springs(z);
  time_ties += seconds_since(t0);
  const StepResult status =
      far_field.finish_step(std::vector<double>(q.data(), q.data() + q.size()));
  if (!status.taken)
  {
    chain.valid = false;
    return status;
  }
  t0 = Clock::now();
  const std::vector<double> at_ties = far_field.point_displacements();
  const Eigen::VectorXd w =
      Eigen::Map<const Eigen::VectorXd>(at_ties.data(), static_cast<Eigen::Index>(at_ties.size()));
  const Eigen::VectorXd f = bonded_springs(z - w);
  work_blocks -= 0.5 * (previous_force + f).dot(delta);
  previous_force = f;
  for (std::size_t k = 0; k < ties.size(); ++k)
    set_accepted_forces(k, z.segment<2>(2 * k) - w.segment<2>(2 * k), f.segment<2>(2 * k));
  chain.valid = true;
  chain.dt = step_dt;
  chain.z = z;
  chain.g_k_z = w - w0;
  time_ties += seconds_since(t0);
  return {};
}

dda::Vector2 FarFieldTies::total_force(const std::size_t k) const
{
  const Tie& t = ties[k];
  return (t.forces.normal_force - t.normal.dot(preload.segment<2>(2 * k))) * t.normal +
         (t.forces.shear_force - t.tangent.dot(preload.segment<2>(2 * k))) * t.tangent;
}

void FarFieldTies::set_accepted_forces(const std::size_t k, const dda::Vector2& stretch,
                                       const dda::Vector2& spring_force)
{
  Tie& t = ties[k];
  t.stretch = stretch;
  t.forces = t.trial;
  const dda::Vector2& f = spring_force;
  t.forces.normal_force = t.normal.dot(f);
  // A sliding tie keeps the trial's shear force, the Mohr-Coulomb limit at the normal force
  // of the step's end, for the next step to apply (DDA's one-step lag, as System's contacts):
  // the force this step applied is the limit at the previous step's normal force, and taking
  // it would freeze S at the normal force the tie started to slide with.
  if (t.trial.state != dda::ContactState::slide)
    t.forces.shear_force = t.tangent.dot(f);
}

TieCounts FarFieldTies::counts() const
{
  TieCounts c;
  for (const Tie& t : ties)
    switch (t.forces.state)
    {
    case dda::ContactState::lock:
      ++(t.forces.intact ? c.intact : c.lock);
      break;
    case dda::ContactState::slide:
      ++c.slide;
      break;
    case dda::ContactState::open:
      ++c.open;
      break;
    }
  return c;
}

double FarFieldTies::work_on_far_field() const
{
  return far_field.work_of_springs();
}

} // namespace ddafem::coupling
