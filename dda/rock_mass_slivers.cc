// Slivers of the rock mass: blocks below the size criteria merged into the neighbouring block
// with which they share the longest boundary (dda/rock_mass_arrangement.h).
#include "dda/rock_mass_arrangement.h"

#include <algorithm>
#include <utility>

namespace ddafem::dda::rock_mass_internal
{
/// One pass of merging: each sliver (smallest first) whose neighbouring block with the longest
/// shared boundary was not involved in a merge of this pass is joined to it by removing the
/// edges they share. Returns the number of merges.
std::size_t merge_pass(Arrangement& arrangement, const SliverCriteria& criteria)
{
  struct Candidate
  {
    Face face;
    std::size_t index = 0;
    double area = 0.0;
    std::size_t neighbour = 0; ///< face index of the block sharing the longest boundary
  };
  std::vector<Face> faces;
  std::vector<Candidate> slivers;
  for (auto f = arrangement.faces_begin(); f != arrangement.faces_end(); ++f)
  {
    faces.push_back(f);
    if (!f->data().block)
      continue;
    double perimeter = 0.0;
    std::vector<std::pair<std::size_t, double>> shared; // (face index, length [m])
    for (const Halfedge h : separating_halfedges(f))
    {
      const double l = length(h);
      perimeter += l;
      const FaceInfo& other = h->twin()->face()->data();
      if (!other.block)
        continue;
      const auto it = std::find_if(shared.begin(), shared.end(),
                                   [&](const auto& s) { return s.first == other.index; });
      if (it == shared.end())
        shared.emplace_back(other.index, l);
      else
        it->second += l;
    }
    const double area = CGAL::to_double(face_area(f));
    if (shared.empty() || !criteria.is_sliver(area, perimeter))
      continue;
    // Longest shared boundary; ties to the lower face index (deterministic).
    const auto best = std::min_element(shared.begin(), shared.end(),
                                       [](const auto& a, const auto& b) {
                                         return a.second > b.second ||
                                                (a.second == b.second && a.first < b.first);
                                       });
    slivers.push_back({f, f->data().index, area, best->first});
  }
  std::sort(slivers.begin(), slivers.end(),
            [](const Candidate& a, const Candidate& b)
            { return a.area < b.area || (a.area == b.area && a.index < b.index); });

  // Faces deleted or grown by a merge are not looked at again in this pass.
  std::vector<bool> touched(faces.size(), false);
  std::size_t n_merged = 0;
  for (const Candidate& s : slivers)
  {
    if (touched[s.index] || touched[s.neighbour])
      continue;
    touched[s.index] = touched[s.neighbour] = true;
    const Face neighbour = faces[s.neighbour];
    std::vector<Halfedge> shared;
    for (const Halfedge h : separating_halfedges(s.face))
      if (h->twin()->face() == neighbour)
        shared.push_back(h);
    for (const Halfedge h : shared)
      arrangement.remove_edge(h);
    ++n_merged;
  }
  return n_merged;
}

} // namespace ddafem::dda::rock_mass_internal
