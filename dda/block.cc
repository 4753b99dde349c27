#include "dda/block.h"

#include "dda/submatrices.h"

namespace ddafem::dda
{
Block::Block(std::size_t material_, std::vector<Point> vertices_)
    : material(material_), vertices(std::move(vertices_)), moments(polygon_moments(vertices)),
      initial_vertices(vertices), initial_moments(moments), initial_centroid(moments.centroid)
{
}

void Block::apply_increment(const Vector6& d, const Eigen::Matrix3d& elasticity, bool about_initial)
{
  const Point c = about_initial ? initial_centroid : moments.centroid;
  for (std::size_t k = 0; k < vertices.size(); ++k)
    vertices[k] += displacement_at(c, about_initial ? initial_vertices[k] : vertices[k], d);
  if (about_initial)
    moments.centroid += d.head<2>(); // T about the centroid moves it by (u0, v0) exactly
  else
    moments = polygon_moments(vertices);
  const Voigt de = d.segment<3>(3);
  strain += de;
  stress += elasticity * de;
}

} // namespace ddafem::dda
