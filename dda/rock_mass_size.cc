// How large a rock mass is before it is generated (rock_mass.h): its blocks, the edges of the
// arrangement that cuts them, and the refusals of a rock mass or an opening beyond the memory
// limits, naming the key to change and a value that fits.
#include "common/format.h"
#include "dda/geometry.h"
#include "dda/rock_mass.h"
#include "dda/rock_mass_arrangement.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace ddafem::dda
{
using rock_mass_internal::extent;

namespace
{
/// The jointed fraction of the set's lines [-].
double persistence(const JointSet& set)
{
  return set.persistent() ? 1.0 : set.trace_length / (set.trace_length + set.bridge);
}

/// How often traces of sets a and b cross in a region of `area` [m^2].
double crossings(const JointSet& a, const JointSet& b, double area)
{
  const double crossing = std::abs(std::sin((a.dip - b.dip) * M_PI / 180.0));
  return area * crossing * persistence(a) * persistence(b) / (a.spacing * b.spacing);
}

/// The set with the closest spacing (the first of equals).
std::size_t closest_set(const RockMassDescription& d)
{
  std::size_t k = 0;
  for (std::size_t s = 1; s < d.joint_sets.size(); ++s)
    if (d.joint_sets[s].spacing < d.joint_sets[k].spacing)
      k = s;
  return k;
}

/// The chord tolerance that gives the opening's arcs at most `sides` sides in all [m], the inverse
/// of opening_side_count: a chord over the angle a deviates r (1 - cos(a / 2)) = 2 r sin^2(a / 4).
double tolerance_for(const Opening& o, double sides)
{
  const auto deviation = [](double r, double a)
  { return 2.0 * r * std::pow(std::sin(0.25 * a), 2); };
  if (o.shape == Opening::Shape::circle)
    return deviation(o.radius, 2.0 * M_PI / std::floor(sides));
  const double chords = std::floor(sides) - (o.wall_height > 0.0 ? 3.0 : 1.0);
  return deviation(0.5 * o.width, M_PI / std::max(chords, 4.0));
}

/// The refusal by the blocks' memory, if they do not fit.
std::optional<RockMassTooLarge> refuse_blocks(const RockMassDescription& d,
                                              std::size_t n_other_blocks,
                                              const ResourceLimits& limits)
{
  const double n_blocks = estimate_block_count(d) + static_cast<double>(n_other_blocks);
  if (limits.fits(MemoryModel::of_blocks(n_blocks)) || d.joint_sets.empty())
    return std::nullopt;
  const double n_fit = std::max(
      MemoryModel::blocks_within(limits.memory) - static_cast<double>(n_other_blocks), 1.0);
  RockMassTooLarge refusal;
  refusal.joint_set = closest_set(d);
  refusal.message =
      "about " + format_number(std::round(n_blocks)) + " blocks would need " +
      limits.too_much(MemoryModel::of_blocks(n_blocks)) + ": expected a spacing of at least " +
      format_significant(d.joint_sets[refusal.joint_set].spacing * std::sqrt(n_blocks / n_fit), 3) +
      " m (with the other sets' spacings scaled alike)";
  return refusal;
}

/// The key that drives the arrangement's size, its largest part, and what is expected of it to
/// bring the edges within `fit`.
RockMassTooLarge shrink_largest_part(const RockMassDescription& d, const ArrangementEstimate& a,
                                     double fit)
{
  const double edges = a.edges();
  std::size_t set = 0;
  for (std::size_t s = 1; s < a.traces.size(); ++s)
    if (a.traces[s] > a.traces[set])
      set = s;
  const double traces = a.traces.empty() ? 0.0 : a.traces[set];
  const double largest = std::max({a.listed, a.curved_sides, traces, 2.0 * a.crossings});
  // The factor on that part that brings the whole within the limit (the others kept); where the
  // others alone are beyond it, the factor on the whole.
  const double rest = edges - largest;
  // 1 % to spare, so that the value suggested, rounded to 3 digits, fits.
  const double factor = 0.99 * (rest < fit ? (fit - rest) / largest : fit / edges);
  RockMassTooLarge refusal;
  if (largest == traces && !d.joint_sets[set].persistent())
  {
    const JointSet& j = d.joint_sets[set];
    refusal.key = RockMassTooLarge::Key::trace_length;
    refusal.joint_set = set;
    refusal.message = "about " + format_number(std::round(traces)) +
                      " traces of this set: expected a trace_length + bridge of at least " +
                      format_significant((j.trace_length + j.bridge) / factor, 3) +
                      " m (with the persistence " + format_significant(persistence(j), 3) +
                      " kept)";
  }
  else if (largest == a.curved_sides)
  {
    refusal.key = RockMassTooLarge::Key::chord_tolerance;
    refusal.message = "about " + format_number(std::round(a.curved_sides)) +
                      " sides of the openings' arcs: expected a chord_tolerance of at least " +
                      format_significant(d.chord_tolerance / (factor * factor), 3) + " m";
  }
  else if (largest == a.listed)
  {
    refusal.key = RockMassTooLarge::Key::joints;
    refusal.message = format_number(d.joints.size()) +
                      " explicit joints and the region's and polygon openings' vertices: "
                      "expected at most " +
                      format_number(std::floor(a.listed * factor)) + " of them";
  }
  else
  {
    // The crossings (a persistent set's lines are never the largest part here: each line adds
    // a block, and refuse_blocks refuses 24 kB blocks before their 4.5 kB edges).
    refusal.joint_set = closest_set(d);
    refusal.message =
        "about " + format_number(std::round(a.crossings)) +
        " crossings of traces: expected a spacing of at least " +
        format_significant(d.joint_sets[refusal.joint_set].spacing / std::sqrt(factor), 3) +
        " m (with the other sets' spacings scaled alike)";
  }
  return refusal;
}
/// The lines of set s across the region, one per spacing over its extent (at most its width
/// normal to the set).
double lines_across(const RockMassDescription& d, const JointSet& s)
{
  return extent(d.region) / s.spacing;
}
} // namespace

double estimate_block_count(const RockMassDescription& d)
{
  const double area = std::abs(signed_area(d.region));
  double blocks = 1.0;
  for (std::size_t i = 0; i < d.joint_sets.size(); ++i)
  {
    const JointSet& a = d.joint_sets[i];
    blocks += lines_across(d, a);
    for (std::size_t j = i + 1; j < d.joint_sets.size(); ++j)
      blocks += crossings(a, d.joint_sets[j], area);
  }
  return blocks;
}

double ArrangementEstimate::edges() const
{
  double n = listed + curved_sides + 2.0 * crossings;
  for (const double t : traces)
    n += t;
  return n;
}

ArrangementEstimate estimate_arrangement(const RockMassDescription& d)
{
  const double area = std::abs(signed_area(d.region));
  ArrangementEstimate a;
  a.listed = static_cast<double>(d.region.size() + d.joints.size());
  for (const Opening& o : d.openings)
    (o.shape == Opening::Shape::polygon ? a.listed : a.curved_sides) +=
        opening_side_count(o, d.chord_tolerance);
  for (std::size_t i = 0; i < d.joint_sets.size(); ++i)
  {
    const JointSet& s = d.joint_sets[i];
    const double lines = lines_across(d, s);
    a.traces.push_back(s.persistent() ? lines
                                      : lines + area / (s.spacing * (s.trace_length + s.bridge)));
    for (std::size_t j = i + 1; j < d.joint_sets.size(); ++j)
      a.crossings += crossings(s, d.joint_sets[j], area);
  }
  return a;
}

std::optional<RockMassTooLarge> refuse_beyond(const RockMassDescription& d,
                                              std::size_t n_other_blocks,
                                              const ResourceLimits& limits)
{
  if (auto refusal = refuse_blocks(d, n_other_blocks, limits))
    return refusal;
  const ArrangementEstimate a = estimate_arrangement(d);
  const double bytes = MemoryModel::of_arrangement(a.edges());
  if (limits.fits(bytes))
    return std::nullopt;
  const double fit = std::max(MemoryModel::arrangement_edges_within(limits.memory), 1.0);
  RockMassTooLarge refusal = shrink_largest_part(d, a, fit);
  refusal.message = "the arrangement that cuts the blocks, about " +
                    format_number(std::round(a.edges())) + " edges, would need " +
                    limits.too_much(bytes) + "; " + refusal.message;
  return refusal;
}

std::optional<std::string> refuse_opening(const Opening& opening, double chord_tolerance,
                                          const ResourceLimits& limits)
{
  if (opening.shape == Opening::Shape::polygon)
    return std::nullopt; // its vertices are listed in the scene: refuse_beyond counts them
  const double sides = opening_side_count(opening, chord_tolerance);
  const double bytes = MemoryModel::of_arrangement(sides);
  const bool too_many = !(sides <= max_opening_sides);
  if (!too_many && limits.fits(bytes))
    return std::nullopt;
  const double fit = too_many ? max_opening_sides
                              : std::max(MemoryModel::arrangement_edges_within(limits.memory), 8.0);
  return "within a chord tolerance of " + format_number(chord_tolerance) + " m its arcs have " +
         format_number(std::round(sides)) + " sides, " +
         (too_many ? "more than the " + format_number(max_opening_sides) +
                         " an opening may have (the blocks around it would take long to set up)"
                   : "which would need " + limits.too_much(bytes)) +
         ": expected a chord_tolerance of at least " +
         format_significant(1.005 * tolerance_for(opening, fit), 3) + " m"; // rounded up
}

} // namespace ddafem::dda
