#include "vorodec/model/polygon.hpp"

namespace vorodec::model {

MassProperties mass_properties(std::span<const geometry::Point> polygon) {
  const std::size_t n = polygon.size();
  const geometry::Point origin = polygon[0];
  double a2 = 0, cx = 0, cy = 0, ixx = 0, iyy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const geometry::Point p = polygon[i] - origin;
    const geometry::Point q = polygon[(i + 1) % n] - origin;
    const double a = p.x * q.y - q.x * p.y;
    a2 += a;
    cx += (p.x + q.x) * a;
    cy += (p.y + q.y) * a;
    iyy += (p.x * p.x + p.x * q.x + q.x * q.x) * a;
    ixx += (p.y * p.y + p.y * q.y + q.y * q.y) * a;
  }
  MassProperties m;
  m.area = 0.5 * a2;
  const double lcx = cx / (3.0 * a2), lcy = cy / (3.0 * a2);
  m.centroid = {origin.x + lcx, origin.y + lcy};
  m.polar_moment = (ixx + iyy) / 12.0 - m.area * (lcx * lcx + lcy * lcy);
  return m;
}

}  // namespace vorodec::model
