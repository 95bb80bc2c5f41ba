#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "vorodec/geometry/zone_mesh.hpp"

namespace vorodec::geometry {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
using FaceBase = CGAL::Delaunay_mesh_face_base_2<Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
constexpr std::uint32_t unnumbered = 0xffffffffu;

// CGAL's size criteria with the size bound read from a field at each triangle's centroid.
class GradedCriteria : public Criteria {
 public:
  GradedCriteria(double aspect_bound, const ZoneSize& size)
      : Criteria::Base(aspect_bound), Criteria(aspect_bound, 1.0), size_(&size) {}

  class Is_bad : public Criteria::Is_bad {
   public:
    Is_bad(double aspect_bound, const ZoneSize& size, const Kernel& geom)
        : Criteria::Is_bad(aspect_bound, 1.0, geom), size_(&size) {}
    using Criteria::Is_bad::operator();
    CGAL::Mesh_2::Face_badness operator()(const Cdt::Face_handle& fh, Quality& q) const {
      const auto& pa = fh->vertex(0)->point();
      const auto& pb = fh->vertex(1)->point();
      const auto& pc = fh->vertex(2)->point();
      std::array<double, 3> sq{CGAL::to_double(CGAL::squared_distance(pb, pc)),
                               CGAL::to_double(CGAL::squared_distance(pc, pa)),
                               CGAL::to_double(CGAL::squared_distance(pa, pb))};
      std::sort(sq.begin(), sq.end());
      const Point centroid{(pa.x() + pb.x() + pc.x()) / 3, (pa.y() + pb.y() + pc.y()) / 3};
      const double bound = (*size_)(centroid);
      q.second = sq[2] / (bound * bound);
      if (q.size() > 1) {
        q.first = 1;
        return CGAL::Mesh_2::IMPERATIVELY_BAD;
      }
      const double area = 2 * CGAL::to_double(CGAL::area(pa, pb, pc));
      q.first = area * area / (sq[2] * sq[1]);
      return q.sine() < this->B ? CGAL::Mesh_2::BAD : CGAL::Mesh_2::NOT_BAD;
    }

   private:
    const ZoneSize* size_;
  };
  Is_bad is_bad_object() const { return Is_bad(this->bound(), *size_, this->traits); }

 private:
  const ZoneSize* size_;
};

// Builds the CDT of the polygon and refines it with `criteria`.
template <class C>
ZoneMesh mesh_with(std::span<const Point> polygon, const C& criteria);
}  // namespace

ZoneMesh mesh_polygon(std::span<const Point> polygon, double zone_size) {
  // 0.125 bounds (sin of the smallest angle)^2 from below: about 20.7 degrees.
  return mesh_with(polygon, Criteria(0.125, zone_size));
}

ZoneMesh mesh_polygon(std::span<const Point> polygon, const ZoneSize& zone_size) {
  return mesh_with(polygon, GradedCriteria(0.125, zone_size));
}

namespace {
template <class C>
ZoneMesh mesh_with(std::span<const Point> polygon, const C& criteria) {
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> corners;
  for (const Point& p : polygon) corners.push_back(cdt.insert(Cdt::Point(p.x, p.y)));
  for (std::size_t i = 0; i < corners.size(); ++i)
    cdt.insert_constraint(corners[i], corners[(i + 1) % corners.size()]);
  CGAL::refine_Delaunay_mesh_2(cdt, criteria);

  ZoneMesh mesh;
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v)
    v->info() = unnumbered;
  // Boundary gridpoints first, edge by edge in polygon order, each edge's points by position.
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point a = polygon[i], b = polygon[(i + 1) % n];
    const Point e = b - a;
    const double len2 = dot(e, e), tol = 1e-9 * std::sqrt(len2);
    std::vector<std::pair<double, Cdt::Vertex_handle>> on_edge;
    for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
      const Point p{v->point().x(), v->point().y()};
      const double s = dot(p - a, e) / len2;
      if (s < 0.0 || s >= 1.0) continue;  // the edge's end corner starts the next edge
      if (std::abs(cross(e, p - a)) / std::sqrt(len2) > tol) continue;
      on_edge.push_back({s, v});
    }
    std::sort(on_edge.begin(), on_edge.end(),
              [](const auto& l, const auto& r) { return l.first < r.first; });
    for (auto& [s, v] : on_edge) {
      if (v->info() != unnumbered) continue;
      v->info() = static_cast<std::uint32_t>(mesh.points.size());
      mesh.boundary.push_back(v->info());
      mesh.points.push_back({v->point().x(), v->point().y()});
    }
  }
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
    if (v->info() != unnumbered) continue;
    v->info() = static_cast<std::uint32_t>(mesh.points.size());
    mesh.points.push_back({v->point().x(), v->point().y()});
  }
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    // CGAL faces are counter-clockwise.
    mesh.zones.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  }
  if (mesh.boundary.size() < n)
    throw std::runtime_error("zoning lost a corner of a block: degenerate polygon");
  return mesh;
}
}  // namespace

}  // namespace vorodec::geometry
