#include "dda/block.h"

#include "dda/submatrices.h"

namespace ddafem::dda
{
Block::Block(std::size_t material_, std::vector<Point> vertices_)
    : material(material_), vertices(std::move(vertices_)), moments(polygon_moments(vertices)),
      initial_centroid(moments.centroid)
{
}

void Block::apply_increment(const Vector6& d, const Eigen::Matrix3d& elasticity)
{
  const Point c = moments.centroid;
  for (Point& v : vertices)
    v += displacement_matrix(c, v) * d;
  moments = polygon_moments(vertices);
  const Voigt de = d.segment<3>(3);
  strain += de;
  stress += elasticity * de;
}

} // namespace ddafem::dda
