// The exact signed area of a polygon with CGAL's lazy exact kernel (Epeck), without its depth
// limit. A lazy number remembers how it was computed: a running sum of n terms is a chain n
// deep, which CGAL evaluates and frees recursively, so CGAL::polygon_area_2 on a polygon of a
// few hundred thousand vertices (an opening's circle within a chord tolerance of 1e-10 m: 385,000
// sides) overflowed an 8 MB stack when the area was destroyed.
#pragma once

#include <cstddef>
#include <iterator>

namespace ddafem::dda
{
/// Partial sums of more terms are made exact, which cuts the chain (CGAL prunes an exact lazy
/// number's history): the deepest chain polygon_area holds.
constexpr std::size_t exact_area_chain = 4096;

/// Signed area of the polygon through the points [first, last) of `kernel` [m^2], anticlockwise
/// positive: the fan of triangles from the first point that CGAL::polygon_area_2 sums, in its
/// order, so that a polygon of up to exact_area_chain + 1 vertices gets the very value (and
/// approximation) it gets; beyond, every exact_area_chain triangles the partial sum is made
/// exact. 0 for fewer than 3 points.
template <typename Iterator, typename Kernel>
typename Kernel::FT polygon_area(Iterator first, Iterator last, const Kernel& kernel)
{
  typename Kernel::FT area(0);
  if (first == last || std::next(first) == last)
    return area;
  const auto triangle_area = kernel.compute_area_2_object();
  Iterator second = std::next(first), third = second;
  std::size_t n_terms = 0;
  while (++third != last)
  {
    area = area + triangle_area(*first, *second, *third);
    second = third;
    if (++n_terms % exact_area_chain == 0)
      area.exact();
  }
  return area;
}

} // namespace ddafem::dda
