#include "dda/yield_acceleration.h"

#include <algorithm>
#include <cmath>

namespace ddafem::dda
{
namespace
{
/// The values of a with c0 - a c1 >= 0 for every (c0, c1): an interval [lo, hi] (maybe empty).
struct Interval
{
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();

  void require(double c0, double c1)
  {
    const double eps = 1e-12 * (std::abs(c0) + 1.0);
    if (std::abs(c1) <= 1e-14)
    {
      if (c0 < -eps)
        hi = lo - 1.0; // never
      return;
    }
    if (c1 > 0.0)
      hi = std::min(hi, c0 / c1);
    else
      lo = std::max(lo, c0 / c1);
  }
  bool empty() const { return lo > hi; }
  /// The value of smallest magnitude in the interval.
  double closest_to_zero() const { return lo > 0.0 ? lo : (hi < 0.0 ? hi : 0.0); }
};

/// Keeps the mode if the interval's value closest to 0 is a smaller |a| than `best`'s.
void keep(YieldAcceleration& best, const Interval& interval, YieldMode mode, std::size_t edge)
{
  if (interval.empty())
    return;
  const double a = interval.closest_to_zero();
  if (std::abs(a) < best.a_y)
    best = {std::abs(a), a < 0.0 ? -1.0 : 1.0, mode, edge};
}
} // namespace

std::vector<BlockFace> block_faces(const std::vector<Point>& polygon,
                                   const std::vector<std::pair<Point, Point>>& opening_segments,
                                   const std::vector<double>& tan_friction, double tol)
{
  std::vector<BlockFace> faces;
  const std::size_t n = polygon.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    const Point a = polygon[k], b = polygon[(k + 1) % n];
    const Point mid = 0.5 * (a + b);
    const bool on_opening = std::any_of(opening_segments.begin(), opening_segments.end(),
                                        [&](const std::pair<Point, Point>& s)
                                        {
                                          const Vector2 e = s.second - s.first;
                                          const double t = std::clamp(
                                              (mid - s.first).dot(e) / e.squaredNorm(), 0.0, 1.0);
                                          return (s.first + t * e - mid).norm() <= tol;
                                        });
    if (on_opening || (b - a).norm() == 0.0)
      continue;
    const Vector2 tangent = (b - a).normalized();
    // Anticlockwise polygon: the inside is on the left of the edge.
    faces.push_back({k, Vector2(-tangent.y(), tangent.x()), tangent, tan_friction[k]});
  }
  return faces;
}

YieldAcceleration yield_acceleration(const std::vector<BlockFace>& faces, const Vector2& g,
                                     const Vector2& d)
{
  YieldAcceleration best;
  // Lift-off: (g - a d) . n_j >= 0 on every face.
  Interval lift;
  for (const BlockFace& f : faces)
    lift.require(g.dot(f.normal), d.dot(f.normal));
  keep(best, lift, YieldMode::lift_off, 0);
  // Sliding on face i along s = +-t_i.
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (const double sense : {1.0, -1.0})
    {
      const Vector2 s = sense * faces[i].tangent;
      const bool admissible = std::all_of(faces.begin(), faces.end(),
                                          [&](const BlockFace& f)
                                          { return &f == &faces[i] || s.dot(f.normal) >= -1e-9; });
      if (!admissible)
        continue;
      const Vector2& n = faces[i].normal;
      const double mu = faces[i].tan_friction;
      Interval slide;
      slide.require(-g.dot(n), -d.dot(n));                               // N >= 0
      slide.require(g.dot(s) + mu * g.dot(n), d.dot(s) + mu * d.dot(n)); // drives past friction
      keep(best, slide, YieldMode::slide, faces[i].edge);
    }
  if (best.a_y <= 1e-9 * g.norm()) // round-off of a face parallel to the shaking
    best.a_y = 0.0;
  return best;
}

} // namespace ddafem::dda
