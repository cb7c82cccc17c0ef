/// @file polygon_mesher.cpp
/// mesh_polygon: input validation, boundary splitting, constrained Delaunay triangulation, domain
/// marking by nesting parity and Delaunay refinement (CGAL, exact predicates / inexact
/// constructions). Every CGAL type stays in this translation unit.
#include <lagfsi/meshing/primitives.hpp>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Delaunay_mesher_no_edge_refinement_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <deque>
#include <functional>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

namespace lagfsi::meshing {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_2;
using Segment = K::Segment_2;
// Vertex info: output node index (-1 when the vertex is not used by an in-domain face).
using Vb = CGAL::Triangulation_vertex_base_with_info_2<Index, K>;
// Face info: nesting level (number of constraints crossed from the infinite face), -1 = unvisited.
using Fb = CGAL::Triangulation_face_base_with_info_2<int, K, CGAL::Delaunay_mesh_face_base_2<K>>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
/// The size criterion with a local size: a face is imperatively bad when its longest edge exceeds
/// `scale` times size(centroid) (the uniform criterion when no size function is given).
class Criteria : public CGAL::Delaunay_mesh_size_criteria_2<CDT> {
 public:
  using Base = CGAL::Delaunay_mesh_size_criteria_2<CDT>;
  using SizeFunction = std::function<double(const Vec2&)>;
  Criteria(double aspect_bound, double size_bound, SizeFunction size = nullptr, double scale = 1.0)
      : Base(aspect_bound, size_bound), size_(std::move(size)), scale_(scale) {}

  class Is_bad : public Base::Is_bad {
   public:
    Is_bad(const Base::Is_bad& uniform, const SizeFunction* size, double scale)
        : Base::Is_bad(uniform), size_(size), scale_(scale) {}
    using Base::Is_bad::operator();
    CGAL::Mesh_2::Face_badness operator()(const CDT::Face_handle& fh, Quality& q) const {
      const CGAL::Mesh_2::Face_badness uniform = Base::Is_bad::operator()(fh, q);
      if (size_ == nullptr || !*size_ || uniform == CGAL::Mesh_2::IMPERATIVELY_BAD) return uniform;
      const Point& a = fh->vertex(0)->point();
      const Point& b = fh->vertex(1)->point();
      const Point& c = fh->vertex(2)->point();
      const double longest2 =
          std::max({CGAL::to_double(CGAL::squared_distance(a, b)), CGAL::to_double(CGAL::squared_distance(b, c)),
                    CGAL::to_double(CGAL::squared_distance(c, a))});
      const Vec2 centroid((a.x() + b.x() + c.x()) / 3.0, (a.y() + b.y() + c.y()) / 3.0);
      const double s = scale_ * (*size_)(centroid);
      q.second = longest2 / (s * s);
      if (q.size() > 1) {
        q.first = 1;
        return CGAL::Mesh_2::IMPERATIVELY_BAD;
      }
      return uniform;
    }

   private:
    const SizeFunction* size_;
    double scale_;
  };
  Is_bad is_bad_object() const { return Is_bad(Base::is_bad_object(), &size_, scale_); }

 private:
  SizeFunction size_;
  double scale_;
};
/// First pass: refines faces only (a point that would encroach a constrained edge is dropped), so
/// the evenly spaced boundary nodes are kept.
using FaceMesher = CGAL::Delaunay_mesher_no_edge_refinement_2<CDT, Criteria>;
/// Second pass: the standard mesher (it splits encroached constrained edges), for the few faces the
/// first pass could not improve (thin parts of the region, small input angles).
using Mesher = CGAL::Delaunay_mesher_2<CDT, Criteria>;

/// Shape bound B of the Delaunay mesher: B = sin^2(min angle), 0.125 <=> about 20.7 degrees.
constexpr double kShapeBound = 0.125;
/// Size bound of the second pass, relative to h: faces left by the first pass with edges a little
/// longer than h (next to the boundary) are accepted, so that the boundary is split only when the
/// shape criterion needs it.
constexpr double kSecondPassSize = 1.5;
/// Expected number of triangles per unit of area / h^2 (about 1 / 0.43).
constexpr double kAreaPerElement = 0.43;

[[noreturn]] void fail(const std::string& why) { throw std::invalid_argument("mesh_polygon: " + why); }
/// The mesh would pass the caller's max_elements.
[[noreturn]] void too_large(const std::string& why) { throw MeshTooLarge("mesh_polygon: " + why); }

std::string loop_name(std::size_t loop) {
  return loop == 0 ? std::string("outer loop") : "hole " + std::to_string(loop - 1);
}

double signed_area(const std::vector<Vec2>& loop) {
  double a = 0.0;
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& p = loop[i];
    const Vec2& q = loop[(i + 1) % n];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

Point to_point(const Vec2& v) { return Point(v.x(), v.y()); }

/// A boundary segment of one loop: loop id, index of its first point, its end points.
struct Seg {
  std::size_t loop;
  std::size_t i;
  std::size_t n;  ///< number of points of the loop
  Point p, q;
  double xmin, xmax, ymin, ymax;
};

/// Throws if two segments of the loops intersect other than at the shared vertex of consecutive
/// segments of a loop (or overlap there). Sweep over x-sorted bounding boxes with exact predicates.
void check_simple(const std::vector<const std::vector<Vec2>*>& loops) {
  std::vector<Seg> segs;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const auto& loop = *loops[l];
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2& a = loop[i];
      const Vec2& b = loop[(i + 1) % n];
      if (a == b) {
        std::ostringstream os;
        os << loop_name(l) << " has a repeated point (index " << i << ")";
        fail(os.str());
      }
      segs.push_back({l, i, n, to_point(a), to_point(b), std::min(a.x(), b.x()), std::max(a.x(), b.x()),
                      std::min(a.y(), b.y()), std::max(a.y(), b.y())});
    }
  }
  std::sort(segs.begin(), segs.end(), [](const Seg& s, const Seg& t) { return s.xmin < t.xmin; });
  for (std::size_t s = 0; s < segs.size(); ++s) {
    const Seg& a = segs[s];
    for (std::size_t t = s + 1; t < segs.size() && segs[t].xmin <= a.xmax; ++t) {
      const Seg& b = segs[t];
      if (b.ymin > a.ymax || b.ymax < a.ymin) continue;
      bool bad = false;
      if (a.loop == b.loop && (b.i == (a.i + 1) % a.n || a.i == (b.i + 1) % a.n)) {
        // Consecutive segments: they share a vertex c; they overlap iff the other two end points u
        // and w are on the same ray from c. Loops of 3 points have 3 consecutive pairs.
        auto overlap = [](const Point& u, const Point& c, const Point& w) {
          return CGAL::orientation(u, c, w) == CGAL::COLLINEAR && CGAL::angle(u, c, w) == CGAL::ACUTE;
        };
        if (b.i == (a.i + 1) % a.n) bad = bad || overlap(a.p, a.q, b.q);  // a.q == b.p
        if (a.i == (b.i + 1) % a.n) bad = bad || overlap(b.p, b.q, a.q);  // b.q == a.p
      } else {
        bad = CGAL::do_intersect(Segment(a.p, a.q), Segment(b.p, b.q));
      }
      if (bad) {
        std::ostringstream os;
        os << "self-intersecting boundary: segment " << a.i << " of the " << loop_name(a.loop) << " and segment " << b.i
           << " of the " << loop_name(b.loop) << " intersect";
        fail(os.str());
      }
    }
  }
}

/// Flood fill from the infinite face: faces reached without crossing a constraint get the same
/// level, crossing a constraint adds one. The domain is the set of odd-level faces.
void mark_nesting_levels(CDT& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  std::deque<CDT::Face_handle> next_level{cdt.infinite_face()};
  int level = 0;
  while (!next_level.empty()) {
    std::deque<CDT::Face_handle> current;
    current.swap(next_level);
    while (!current.empty()) {
      CDT::Face_handle f = current.front();
      current.pop_front();
      if (f->info() != -1) continue;
      f->info() = level;
      for (int i = 0; i < 3; ++i) {
        CDT::Face_handle g = f->neighbor(i);
        if (g->info() != -1) continue;
        if (cdt.is_constrained(CDT::Edge(f, i)))
          next_level.push_back(g);
        else
          current.push_back(g);
      }
    }
    ++level;
  }
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f)
    f->set_in_domain(!cdt.is_infinite(f) && f->info() % 2 == 1);
}

/// Rejects a region with a feature far thinner than h: the refinement would need elements of that size
/// and did not finish on a 1e-12 m wide rectangle. The feature size is the smallest distance from a vertex
/// to a segment that does not end at it (any loop); the bound is kMinFeature h.
void check_feature_size(const std::vector<const std::vector<Vec2>*>& loops, double h) {
  constexpr double kMinFeature = 0.02;
  auto distance = [](const Vec2& p, const Vec2& a, const Vec2& b) {
    const Vec2 ab = b - a;
    const double l2 = ab.squaredNorm();
    const double s = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
    return (p - (a + s * ab)).norm();
  };
  for (std::size_t l = 0; l < loops.size(); ++l)
    for (std::size_t i = 0; i < loops[l]->size(); ++i) {
      const Vec2& p = (*loops[l])[i];
      for (std::size_t m = 0; m < loops.size(); ++m) {
        const auto& loop = *loops[m];
        const std::size_t n = loop.size();
        for (std::size_t j = 0; j < n; ++j) {
          const std::size_t k = (j + 1) % n;
          if (m == l && (j == i || k == i)) continue;
          const double d = distance(p, loop[j], loop[k]);
          if (d < kMinFeature * h) {
            std::ostringstream os;
            os << "point " << i << " of " << loop_name(l) << " is " << d << " from segment " << j << " of "
               << loop_name(m) << ", less than " << kMinFeature << " h (h = " << h
               << "): a feature that thin cannot be meshed at this size";
            fail(os.str());
          }
        }
      }
    }
}

/// Rejects a spike or a crack sharper than kMinAngle: the boundary of a 600 m wedge of 0.002 degrees (a
/// coordinate 1000 times too large) took minutes to insert (long chains of edge flips between its two
/// nearly parallel sides) before the refinement's point limit stopped it.
void check_angles(const std::vector<const std::vector<Vec2>*>& loops) {
  constexpr double kMinAngle = 1e-3;  // rad, 0.057 degrees
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const auto& loop = *loops[l];
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 a = loop[(i + n - 1) % n] - loop[i], b = loop[(i + 1) % n] - loop[i];
      if (!(a.squaredNorm() > 0 && b.squaredNorm() > 0)) continue;  // repeated points: check_simple's
      const double angle = std::atan2(std::abs(a.x() * b.y() - a.y() * b.x()), a.dot(b));
      if (angle < kMinAngle) {
        std::ostringstream os;
        os << "the angle at point " << i << " of " << loop_name(l) << " is " << angle * 180.0 / std::numbers::pi
           << " degrees, below " << kMinAngle * 180.0 / std::numbers::pi << ": a spike that sharp cannot be meshed";
        fail(os.str());
      }
    }
  }
}

}  // namespace

TriMesh mesh_polygon(const PolygonRegion& region, double h, double max_elements,
                     const std::function<double(const Vec2&)>& size) {
  // ---- validation
  if (!std::isfinite(h) || h <= 0.0) fail("target size h must be finite and > 0 (got " + std::to_string(h) + ")");
  std::vector<Vec2> outer = region.outer;
  std::vector<const std::vector<Vec2>*> loops{&outer};
  for (const auto& hole : region.holes) loops.push_back(&hole);
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const auto& loop = *loops[l];
    if (loop.size() < 3) fail(loop_name(l) + " has fewer than 3 points");
    for (const Vec2& p : loop)
      if (!std::isfinite(p.x()) || !std::isfinite(p.y())) fail(loop_name(l) + " has a non-finite coordinate");
  }
  if (signed_area(outer) < 0.0) std::reverse(outer.begin(), outer.end());
  double xmin = outer[0].x(), xmax = xmin, ymin = outer[0].y(), ymax = ymin;
  for (const Vec2& p : outer) {
    xmin = std::min(xmin, p.x());
    xmax = std::max(xmax, p.x());
    ymin = std::min(ymin, p.y());
    ymax = std::max(ymax, p.y());
  }
  // Relative threshold: a loop whose area is at round-off level of its bounding box is degenerate.
  const double scale2 =
      std::max((xmax - xmin) * (xmax - xmin) + (ymax - ymin) * (ymax - ymin), std::numeric_limits<double>::min());
  double area = 0.0;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const double a = std::abs(signed_area(*loops[l]));
    if (!(a > 1e-13 * scale2)) fail(loop_name(l) + " has zero area");
    area += l == 0 ? a : -a;
  }
  check_simple(loops);
  check_angles(loops);
  // Holes must lie inside the outer loop and outside one another (loops do not intersect, so one
  // vertex per loop decides).
  std::vector<Point> ring;
  for (const Vec2& v : outer) ring.push_back(to_point(v));
  for (std::size_t l = 1; l < loops.size(); ++l) {
    const Point p = to_point((*loops[l])[0]);
    if (CGAL::bounded_side_2(ring.begin(), ring.end(), p, K()) != CGAL::ON_BOUNDED_SIDE)
      fail(loop_name(l) + " is not inside the outer loop");
    for (std::size_t m = 1; m < loops.size(); ++m) {
      if (m == l) continue;
      std::vector<Point> other;
      for (const Vec2& v : *loops[m]) other.push_back(to_point(v));
      if (CGAL::bounded_side_2(other.begin(), other.end(), p, K()) != CGAL::ON_UNBOUNDED_SIDE)
        fail(loop_name(l) + " is inside " + loop_name(m) + " (nested holes are not supported)");
    }
  }
  if (!(area > 0.0)) fail("the holes cover the whole region");
  const double expected = area / (kAreaPerElement * h * h);
  if (!(expected <= max_elements)) {
    std::ostringstream os;
    os << "about " << expected << " elements expected (area " << area << ", h " << h << "), more than the limit "
       << max_elements;
    too_large(os.str());
  }
  check_feature_size(loops, h);  // after the size check: it compares every vertex with every segment

  // ---- boundary: split every segment into ceil(len / h) equal pieces, insert as constraints
  CDT cdt;
  double boundary_points = 0.0;
  for (const auto* loop : loops)
    for (std::size_t i = 0; i < loop->size(); ++i)
      boundary_points += std::ceil(((*loop)[(i + 1) % loop->size()] - (*loop)[i]).norm() / h);
  if (!(boundary_points <= 4.0 * max_elements)) too_large("too many boundary points for this h");
  for (const auto* loop : loops) {
    const std::size_t n = loop->size();
    CDT::Vertex_handle first, prev;
    CDT::Face_handle hint;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2& a = (*loop)[i];
      const Vec2& b = (*loop)[(i + 1) % n];
      // The (1 - 1e-12) factor keeps exact multiples of h (up to round-off) at len / h pieces.
      const int pieces = std::max(1, static_cast<int>(std::ceil((b - a).norm() / h * (1.0 - 1e-12))));
      for (int k = 0; k < pieces; ++k) {
        const Vec2 x = k == 0 ? a : Vec2(a + (b - a) * (static_cast<double>(k) / pieces));
        CDT::Vertex_handle v = cdt.insert(to_point(x), hint);
        if (prev != CDT::Vertex_handle())
          cdt.insert_constraint(prev, v);
        else
          first = v;
        hint = v->face();  // after the constraint insertion, which may delete faces
        prev = v;
      }
    }
    cdt.insert_constraint(prev, first);
  }

  // ---- domain and refinement
  mark_nesting_levels(cdt);
  // Refinement one point at a time, so that a region whose small angles make it insert far more points than
  // its area suggests stops at the limit (a flag stretched to 210 m took minutes and 5 GB) instead of ending.
  const double max_vertices = max_elements;  // about half the elements, with margin
  auto refine = [&](auto& mesher) {
    mesher.init(/*domain_specified=*/true);
    while (mesher.step_by_step_refine_mesh())
      if (!(static_cast<double>(cdt.number_of_vertices()) <= max_vertices)) {
        std::ostringstream os;
        os << "the refinement needs more than " << max_vertices << " points at h = " << h
           << " (small angles or a region far larger than h)";
        too_large(os.str());
      }
  };
  {
    // With a local size the uniform bound is off (0): each face is held to its own size.
    FaceMesher mesher(cdt, size ? Criteria(kShapeBound, 0.0, size, 1.0) : Criteria(kShapeBound, h));
    refine(mesher);
  }
  {
    Mesher mesher(
        cdt, size ? Criteria(kShapeBound, 0.0, size, kSecondPassSize) : Criteria(kShapeBound, kSecondPassSize * h));
    refine(mesher);
  }

  // ---- output: in-domain faces (counter-clockwise in CGAL), compact numbering in vertex order
  TriMesh mesh;
  mesh.order = 1;
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) v->info() = -1;
  std::size_t nf = 0;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    ++nf;
    for (int i = 0; i < 3; ++i) f->vertex(i)->info() = 0;
  }
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
    if (v->info() < 0) continue;
    v->info() = static_cast<Index>(mesh.nodes.size());
    mesh.nodes.emplace_back(v->point().x(), v->point().y());
  }
  mesh.conn.reserve(3 * nf);
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    for (int i = 0; i < 3; ++i) mesh.conn.push_back(f->vertex(i)->info());
  }
  return mesh;
}

}  // namespace lagfsi::meshing
