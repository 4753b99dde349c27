// The joint traces of the rock mass generator: the lines of each joint set (spacing and position
// perturbed by seeded draws), their traces and bridges, and the explicit joints, as curves of the
// arrangement (dda/rock_mass_arrangement.h).
#include "common/input_error.h"
#include "dda/rock_mass_arrangement.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

namespace ddafem::dda::rock_mass_internal
{
namespace
{
/// Unit vector at `degrees` from +x, exact for multiples of 90 degrees (so that sets at 0 and
/// 90 degrees give exactly rectangular blocks).
Vector2 unit_vector(double degrees)
{
  const double quarter_turns = degrees / 90.0;
  if (quarter_turns == std::round(quarter_turns))
  {
    const long q = ((static_cast<long>(quarter_turns) % 4) + 4) % 4;
    const Vector2 axes[] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    return axes[q];
  }
  const double radians = degrees * M_PI / 180.0;
  return Vector2(std::cos(radians), std::sin(radians));
}

// ---- Random perturbations ----------------------------------------------------------------------

/// Draws of xi for one joint set and direction. The engine and std::seed_seq are specified by
/// the standard, the std:: distributions are not (they differ between standard libraries), so
/// the draws are made here: a seed gives the same joints with any standard library (up to the
/// last bit of std::log and std::cos for normal draws).
class Draws
{
public:
  Draws(std::uint64_t seed, std::size_t set, unsigned stream)
  {
    std::seed_seq sequence{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                           static_cast<std::uint32_t>(set), stream};
    engine.seed(sequence);
  }

  double xi(Distribution distribution)
  {
    if (distribution == Distribution::uniform)
      return 2.0 * unit() - 1.0;
    // Box-Muller: u1 in (0, 1] keeps the logarithm finite.
    const double u1 = 1.0 - unit();
    const double u2 = unit();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

private:
  double unit() { return static_cast<double>(engine() >> 11) * 0x1.0p-53; } ///< [0, 1)
  std::mt19937_64 engine;
};

// ---- Joint traces ------------------------------------------------------------------------------

/// One joint line of a set: its normal position c [m] (n.x = c) and the shift of its trace
/// pattern along the line [m].
struct JointLine
{
  double c = 0.0;
  double phase = 0.0;
};

/// The lines of a set that meet the normal interval [n_lo, n_hi] [m]. Lines are generated from
/// line 0 outwards, one random stream per direction, each line drawing its gap to the next line
/// and its phase: enlarging the region adds lines but keeps the ones it had.
std::vector<JointLine> joint_lines(const JointSet& set, std::size_t set_index, std::uint64_t seed,
                                   double n_lo, double n_hi)
{
  const double walk = std::max(std::abs(n_hi - set.offset), std::abs(set.offset - n_lo));
  if (walk / set.spacing > 1e7)
    throw InputError("joint set " + std::to_string(set_index) + ": line 0 (offset " +
                     format_number(set.offset) + " m) is " + format_number(walk / set.spacing) +
                     " spacings from the far side of the region: expected an offset within 10^7 "
                     "spacings of the region");
  const JointPerturbation& p = set.perturbation;
  const double period = set.persistent() ? 0.0 : set.trace_length + set.bridge;
  std::vector<JointLine> lines;
  for (const int direction : {+1, -1})
  {
    Draws draws(seed, set_index, direction > 0 ? 0 : 1);
    double c = set.offset;
    long k = 0;
    const auto gap = [&]
    {
      double xi = draws.xi(p.distribution);
      while (1.0 + p.spacing * xi < 0.1)
        xi = draws.xi(p.distribution);
      return set.spacing * (1.0 + p.spacing * xi);
    };
    if (direction < 0)
    {
      c -= gap();
      k = -1;
    }
    while (direction > 0 ? c <= n_hi : c >= n_lo)
    {
      const double stagger = (k % 2 == 0) ? 0.0 : 0.5 * period;
      const double phase = stagger + p.position * period * draws.xi(p.distribution);
      if (c >= n_lo && c <= n_hi)
        lines.push_back({c, phase});
      c += direction * gap();
      k += direction;
    }
  }
  return lines;
}

/// Appends the segment from a to b clipped to the box (nothing if they do not cross it).
void append_clipped(const ExactPoint& a, const ExactPoint& b, const Kernel::Iso_rectangle_2& box,
                    CurveSource source, std::vector<Traits::Curve_2>& curves)
{
  const auto clipped = CGAL::intersection(Segment(a, b), box);
  if (!clipped)
    return;
  // CGAL 5 returns a boost::variant: a point where the segment only touches the box.
  if (const Segment* s = boost::get<Segment>(&*clipped))
    if (!s->is_degenerate())
      curves.emplace_back(*s, source);
}

} // namespace

/// The points of a joint line are exact, x = c n + t d in rationals: every trace of the line
/// lies exactly on it (n.d = 0 holds exactly for n = (-d_y, d_x)), and lines meant to pass
/// through one point (offsets 0 through the origin, a corner of the region) do.
std::vector<Traits::Curve_2> joint_curves(const RockMassDescription& d)
{
  const Box bounds = bounding_box(d.region);
  const Point &lower = bounds.lower, &upper = bounds.upper;
  const Kernel::Iso_rectangle_2 box(exact_point(lower), exact_point(upper));
  const Point corners[] = {lower, {upper.x(), lower.y()}, upper, {lower.x(), upper.y()}};
  const double margin = (upper - lower).norm(); // makes persistent traces reach past the box

  std::vector<Traits::Curve_2> curves;
  for (std::size_t s = 0; s < d.joint_sets.size(); ++s)
  {
    const JointSet& set = d.joint_sets[s];
    const Vector2 along = unit_vector(set.dip);
    const Vector2 normal(-along.y(), along.x());
    double n_lo = corners[0].dot(normal), n_hi = n_lo;
    double t_lo = corners[0].dot(along), t_hi = t_lo;
    for (const Point& corner : corners)
    {
      n_lo = std::min(n_lo, corner.dot(normal));
      n_hi = std::max(n_hi, corner.dot(normal));
      t_lo = std::min(t_lo, corner.dot(along));
      t_hi = std::max(t_hi, corner.dot(along));
    }
    const double n_traces =
        (n_hi - n_lo) / set.spacing *
        (set.persistent() ? 1.0 : (t_hi - t_lo) / (set.trace_length + set.bridge) + 1.0);
    if (n_traces > 1e6)
      throw InputError("joint set " + std::to_string(s) + ": about " + format_number(n_traces) +
                       " traces cross the region: expected at most 10^6 (is the spacing, " +
                       format_number(set.spacing) +
                       " m, or the period trace_length + bridge too small for the region?)");
    const CurveSource source{CurveSource::Kind::joint_set, s};
    for (const JointLine& line : joint_lines(set, s, d.seed, n_lo, n_hi))
    {
      const auto at = [&](double t)
      {
        const Kernel::FT c = line.c, tt = t;
        return ExactPoint(c * normal.x() + tt * along.x(), c * normal.y() + tt * along.y());
      };
      if (set.persistent())
      {
        append_clipped(at(t_lo - margin), at(t_hi + margin), box, source, curves);
        continue;
      }
      const double period = set.trace_length + set.bridge;
      // Traces j whose span [phase + j P, phase + j P + L] meets [t_lo, t_hi].
      const double j_first = std::floor((t_lo - line.phase - set.trace_length) / period);
      for (double j = j_first; line.phase + j * period <= t_hi; ++j)
      {
        const double t0 = line.phase + j * period;
        append_clipped(at(t0), at(t0 + set.trace_length), box, source, curves);
      }
    }
  }
  for (std::size_t i = 0; i < d.joints.size(); ++i)
    append_clipped(exact_point(d.joints[i].from), exact_point(d.joints[i].to), box,
                   {CurveSource::Kind::explicit_joint, i}, curves);
  return curves;
}

/// The closed polygon's edges as curves.
void append_polygon(const std::vector<Point>& polygon, CurveSource source,
                    std::vector<Traits::Curve_2>& curves)
{
  for (std::size_t i = 0; i < polygon.size(); ++i)
    curves.emplace_back(
        Segment(exact_point(polygon[i]), exact_point(polygon[(i + 1) % polygon.size()])), source);
}

} // namespace ddafem::dda::rock_mass_internal
