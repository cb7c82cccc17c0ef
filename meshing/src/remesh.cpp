/// @file remesh.cpp
/// PFEM remeshing: CGAL Delaunay triangulation (exact predicates, inexact constructions) of the particle
/// cloud, the domain detection on each Delaunay face (the alpha test, or the advected previous domain:
/// remesh.hpp, DomainDetection), removal of wall/ghost-only faces, free-surface detection by a neighbour
/// check through the triangulation; a part's share of it for a run divided among processes (remesh_part). The
/// geometric particle-quality helpers are in particle_quality.cpp. Every CGAL type stays in this translation unit.
#include <lagfsi/meshing/remesh.hpp>

#include <lagfsi/meshing/partition.hpp>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace lagfsi::meshing {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_2;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<Index, K>;       // info: particle index
using Fb = CGAL::Triangulation_face_base_with_info_2<std::uint8_t, K>;  // info: kKept, kReported bits
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using DT = CGAL::Delaunay_triangulation_2<K, Tds>;

[[noreturn]] void fail(const char* where, const std::string& what) {
  throw std::invalid_argument(std::string(where) + ": " + what);
}

std::string point_str(const Vec2& p) {
  std::ostringstream s;
  s.precision(17);
  s << '(' << p.x() << ", " << p.y() << ')';
  return s.str();
}

/// Finite coordinates, an index range that fits Index; returns the duplicate tolerance squared
/// (1e-12 of the bounding-box diagonal, squared).
double check_points(const std::vector<Vec2>& points, const char* where) {
  if (points.size() > static_cast<std::size_t>(std::numeric_limits<Index>::max()))
    fail(where, "too many points (" + std::to_string(points.size()) + ")");
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec2& p = points[i];
    if (!(std::isfinite(p.x()) && std::isfinite(p.y())))
      fail(where, "point " + std::to_string(i) + " has a non-finite coordinate");
    x0 = std::min(x0, p.x());
    x1 = std::max(x1, p.x());
    y0 = std::min(y0, p.y());
    y1 = std::max(y1, p.y());
  }
  if (points.empty()) return 0.0;
  const double tol = 1e-12 * std::hypot(x1 - x0, y1 - y0);
  return tol * tol;
}

/// Called when the triangulation has fewer vertices than the points inserted (`ids`, or all of `points`): CGAL
/// merged exact duplicates.
[[noreturn]] void throw_merged_duplicates(const DT& dt, const std::vector<Vec2>& points, const std::vector<Index>* ids,
                                          const char* where) {
  std::vector<std::uint8_t> kept(points.size(), 0);
  for (auto v : dt.finite_vertex_handles()) kept[static_cast<std::size_t>(v->info())] = 1;
  const std::size_t m = ids != nullptr ? ids->size() : points.size();
  const auto id = [&](std::size_t k) { return ids != nullptr ? static_cast<std::size_t>((*ids)[k]) : k; };
  std::size_t first = 0;
  while (first < m && kept[id(first)]) ++first;
  const std::size_t lost = id(first);
  std::size_t twin = 0;
  while (twin < m && !(kept[id(twin)] && points[id(twin)] == points[lost])) ++twin;
  std::ostringstream s;
  s << (m - dt.number_of_vertices()) << " duplicate point(s), e.g. point " << lost << " equals point "
    << (twin < m ? id(twin) : lost) << " at " << point_str(points[lost]);
  fail(where, s.str());
}

[[noreturn]] void throw_near_duplicate(Index i, Index j, const std::vector<Vec2>& points, const char* where) {
  std::ostringstream s;
  s << "duplicate points: " << i << " " << point_str(points[static_cast<std::size_t>(i)]) << " and " << j << " "
    << point_str(points[static_cast<std::size_t>(j)]) << " are closer than 1e-12 of the bounding box";
  fail(where, s.str());
}

/// One range insertion of (point, index) pairs (CGAL sorts them spatially): all of `points`, or those of `ids`
/// (each vertex keeps its index in `points`); then the exact-duplicate check. Near duplicates are checked by the
/// callers on the faces (or edges in dimension 1).
void build(DT& dt, const std::vector<Vec2>& points, const char* where, const std::vector<Index>* ids = nullptr) {
  std::vector<std::pair<Point, Index>> input;
  const std::size_t m = ids != nullptr ? ids->size() : points.size();
  input.reserve(m);
  for (std::size_t k = 0; k < m; ++k) {
    const Index i = ids != nullptr ? (*ids)[k] : static_cast<Index>(k);
    const Vec2& p = points[static_cast<std::size_t>(i)];
    input.emplace_back(Point(p.x(), p.y()), i);
  }
  dt.insert(input.begin(), input.end());
  if (dt.number_of_vertices() < m) throw_merged_duplicates(dt, points, ids, where);
}

/// Which faces and edges a call reports: all of them (remesh), or one part's (remesh_part: a face whose centroid
/// lies in the part's box, an edge whose lower particle is the part's).
struct Reported {
  const SpacePartition* partition = nullptr;
  int part = 0;
  const std::vector<Vec2>* points = nullptr;
  bool face(Index a, Index b, Index c) const {
    if (partition == nullptr) return true;
    std::array<Index, 3> t{a, b, c};
    std::sort(t.begin(), t.end());  // the same centroid, to the bit, in every part
    const auto at = [&](Index i) { return (*points)[static_cast<std::size_t>(i)]; };
    return partition->part_of((at(t[0]) + at(t[1]) + at(t[2])) * (1.0 / 3.0)) == part;
  }
  bool edge(Index a, Index b) const {
    return partition == nullptr || partition->owner()[static_cast<std::size_t>(std::min(a, b))] == part;
  }
};

/// Face flags (the faces' info): kept by the domain detection, and reported by this call.
constexpr std::uint8_t kKept = 1, kReported = 2;

/// Dimension < 2: no faces; check the edges (dimension 1) for near duplicates.
void check_edges_1d(const DT& dt, const std::vector<Vec2>& points, double tol2, const char* where) {
  for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
    const Index i = e->first->vertex(DT::cw(e->second))->info();
    const Index j = e->first->vertex(DT::ccw(e->second))->info();
    if ((points[static_cast<std::size_t>(i)] - points[static_cast<std::size_t>(j)]).squaredNorm() < tol2)
      throw_near_duplicate(i, j, points, where);
  }
}

/// The one Delaunay edge that crosses the segment a -> b, when exactly one does: the face (a, c, d) around a
/// through which the segment leaves and the index of a in it (its edge (c, d) is opposite a), with the face
/// across (c, d) having b as its third vertex. Then the quadrilateral a c b d is strictly convex and flipping
/// (c, d) gives (a, b). Returns false if more than one edge crosses, or the segment leaves the convex hull.
bool single_crossing(const DT& dt, DT::Vertex_handle va, DT::Vertex_handle vb, DT::Face_handle& hit, int& opp) {
  const K::Orientation_2 orient = K().orientation_2_object();
  opp = -1;
  auto fc = dt.incident_faces(va);
  const auto done = fc;
  do {
    if (dt.is_infinite(fc)) continue;
    const int ia = fc->index(va);
    const auto vc = fc->vertex(DT::ccw(ia)), vd = fc->vertex(DT::cw(ia));
    if (orient(va->point(), vc->point(), vb->point()) == CGAL::LEFT_TURN &&
        orient(va->point(), vd->point(), vb->point()) == CGAL::RIGHT_TURN) {
      hit = fc;
      opp = ia;
      break;
    }
  } while (++fc != done);
  if (opp < 0) return false;
  const DT::Face_handle g = hit->neighbor(opp);
  return !dt.is_infinite(g) && g->vertex(g->index(hit)) == vb;
}

std::vector<DT::Vertex_handle> vertex_handles(const DT& dt, std::size_t n) {
  std::vector<DT::Vertex_handle> vh(n);
  for (auto v : dt.finite_vertex_handles()) vh[static_cast<std::size_t>(v->info())] = v;
  return vh;
}

/// Puts the previous domain's boundary edges back into the triangulation where one Delaunay edge crosses them.
/// Particles move within a step, and an edge of the old free surface may no longer be Delaunay in the new
/// cloud: then no new face has it, the two faces across it straddle the old boundary, and whichever side
/// their centroids fall on, the domain gains or loses a sliver of the area. Where exactly one edge (c, d) crosses the
/// old edge (a, b), the quadrilateral a c b d is convex and flipping (c, d) into (a, b) restores the old boundary; the
/// flipped faces are then classified as any other. An edge crossed by more than one Delaunay edge (the boundary folded
/// within a step) is left out. The triangulation is no longer Delaunay at the flipped edges, which is what a
/// constrained Delaunay triangulation with those constraints would give locally (Leyssens et al. 2024 keep the old
/// boundary the same way).
void restore_boundary_edges(DT& dt, const PreviousDomain& previous, std::size_t n, const Reported& reported,
                            int& restored, int& lost) {
  const std::vector<DT::Vertex_handle> vh = vertex_handles(dt, n);
  for (const auto& [a, b] : previous.boundary_edges()) {
    if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= n || static_cast<std::size_t>(b) >= n) continue;
    const DT::Vertex_handle va = vh[static_cast<std::size_t>(a)], vb = vh[static_cast<std::size_t>(b)];
    if (va == DT::Vertex_handle() || vb == DT::Vertex_handle() || dt.is_edge(va, vb)) continue;
    DT::Face_handle hit;
    int opp = -1;
    const int counted = reported.edge(a, b) ? 1 : 0;
    if (!single_crossing(dt, va, vb, hit, opp)) {
      lost += counted;  // more than one edge crosses (a, b), or it leaves the convex hull
      continue;
    }
    const Index c = hit->vertex(DT::ccw(opp))->info(), d = hit->vertex(DT::cw(opp))->info();
    if (previous.is_boundary_edge(c, d)) {
      lost += counted;  // two old boundary edges cross: keep the one the Delaunay triangulation has
      continue;
    }
    dt.flip(hit, opp);
    restored += counted;
  }
}

/// The previous mesh's interior edges, flipped back in with hysteresis (RemeshSettings::keep_edges_angle):
/// an old edge (a, b) crossed by exactly one Delaunay edge (c, d) that is not an old edge is restored when
/// the angles at c and d facing it sum to at most pi + tol (Delaunay: at most pi). Each flip adds an old
/// edge and removes a new one, so the passes end; a later pass may restore an edge that an earlier flip
/// made crossable once.
int keep_previous_edges(DT& dt, const PreviousDomain& previous, std::size_t n, const std::vector<Vec2>& points,
                        double tol, const Reported& reported) {
  const std::vector<DT::Vertex_handle> vh = vertex_handles(dt, n);
  const double limit = std::numbers::pi + tol;
  const auto angle = [&](Index apex, Index p, Index q) {
    const Vec2 u = points[static_cast<std::size_t>(p)] - points[static_cast<std::size_t>(apex)];
    const Vec2 w = points[static_cast<std::size_t>(q)] - points[static_cast<std::size_t>(apex)];
    return std::atan2(std::abs(u.x() * w.y() - u.y() * w.x()), u.dot(w));
  };
  int kept = 0;
  for (int pass = 0; pass < 8; ++pass) {
    int flips = 0, counted = 0;
    for (const auto& [a, b] : previous.edges()) {
      if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= n || static_cast<std::size_t>(b) >= n) continue;
      if (previous.is_boundary_edge(a, b)) continue;  // restore_boundary_edges' business
      const DT::Vertex_handle va = vh[static_cast<std::size_t>(a)], vb = vh[static_cast<std::size_t>(b)];
      if (va == DT::Vertex_handle() || vb == DT::Vertex_handle() || dt.is_edge(va, vb)) continue;
      DT::Face_handle hit;
      int opp = -1;
      if (!single_crossing(dt, va, vb, hit, opp)) continue;
      const Index c = hit->vertex(DT::ccw(opp))->info(), d = hit->vertex(DT::cw(opp))->info();
      if (previous.is_edge(c, d)) continue;
      if (angle(c, a, b) + angle(d, a, b) > limit) continue;
      dt.flip(hit, opp);
      ++flips;
      counted += reported.edge(a, b) ? 1 : 0;
    }
    kept += counted;
    if (flips == 0) break;
  }
  return kept;
}

/// remesh()'s input as its stages read it.
struct RemeshInput {
  const std::vector<Vec2>& points;
  const std::vector<ParticleKind>& kind;
  const std::vector<double>& h;
  const RemeshSettings& settings;
  const PreviousDomain* previous = nullptr;  // the advected or level-set detection's domain; nullptr: alpha
  double tol2 = 0;                           // the duplicate tolerance squared (check_points)
  const char* where = "remesh";
  /// With settings.on_wall: the particles of the previous domain's free surface, those on a boundary edge of it with
  /// neither end on a wall (a particle that has just left a wall, between two particles on it, is not one).
  std::vector<std::uint8_t> on_previous_surface{};
};

/// Checks remesh()'s input (sizes, settings, coordinates, h and kind; std::invalid_argument otherwise) and
/// sets `previous` and `tol2`.
void check_remesh_input(RemeshInput& in) {
  const char* where = in.where;
  const RemeshSettings& settings = in.settings;
  const std::size_t n = in.points.size();
  if (in.kind.size() != n || in.h.size() != n)
    fail(where, "sizes do not match (points " + std::to_string(n) + ", kind " + std::to_string(in.kind.size()) +
                    ", h " + std::to_string(in.h.size()) + ")");
  const double alpha = settings.alpha;
  if (!(std::isfinite(alpha) && alpha > 0)) fail(where, "alpha must be finite and > 0");
  if (settings.detection != DomainDetection::Alpha) {
    if (settings.previous == nullptr || settings.previous->empty())
      fail(where, "the advected and level-set detections need the previous domain");
    if (!(std::isfinite(settings.separation_alpha) && settings.separation_alpha >= alpha))
      fail(where, "separation_alpha must be finite and >= alpha");
    if (!(std::isfinite(settings.level_set_band) && settings.level_set_band >= 0))
      fail(where, "level_set_band must be finite and >= 0");
    if (!(std::isfinite(settings.contact_gap) && settings.contact_gap >= 0))
      fail(where, "contact_gap must be finite and >= 0");
    if (!(std::isfinite(settings.keep_edges_angle) && settings.keep_edges_angle >= 0 &&
          settings.keep_edges_angle < std::numbers::pi / 2))
      fail(where, "keep_edges_angle must be in [0, pi/2)");
    in.previous = settings.previous;
    if (settings.on_wall != nullptr) {
      const std::vector<std::uint8_t>& on_wall = *settings.on_wall;
      if (on_wall.size() != in.points.size()) fail(where, "on_wall's size does not match the points'");
      in.on_previous_surface.assign(in.points.size(), 0);
      for (const auto& [a, b] : settings.previous->boundary_edges()) {
        const auto ia = static_cast<std::size_t>(a), ib = static_cast<std::size_t>(b);
        if (a < 0 || b < 0 || ia >= on_wall.size() || ib >= on_wall.size() || on_wall[ia] || on_wall[ib]) continue;
        in.on_previous_surface[ia] = in.on_previous_surface[ib] = 1;
      }
    }
  }
  in.tol2 = check_points(in.points, where);
  for (std::size_t i = 0; i < n; ++i) {
    if (!(std::isfinite(in.h[i]) && in.h[i] > 0)) fail(where, "h[" + std::to_string(i) + "] must be finite and > 0");
    if (static_cast<std::uint8_t>(in.kind[i]) > static_cast<std::uint8_t>(ParticleKind::Ghost))
      fail(where, "kind[" + std::to_string(i) + "] is not a valid ParticleKind");
  }
}

/// A Delaunay face (a, b, c), counter-clockwise, measured in double from the input coordinates.
struct FaceGeometry {
  Index a, b, c;
  double lab2, lac2, lbc2;  // the squared edge lengths
  double cr;                // 2 * area
  double he;                // the element size h_e = (h_a + h_b + h_c) / 3
  double lll;               // l_ab l_ac l_bc
  int walls;                // its wall and ghost particles
};

/// The face's geometry; throws on a near-duplicate pair of its particles (closer than tol2).
FaceGeometry face_geometry(const RemeshInput& in, const DT::Face_handle& f) {
  const auto& points = in.points;
  const auto& h = in.h;
  const auto& kind = in.kind;
  const Index a = f->vertex(0)->info(), b = f->vertex(1)->info(), c = f->vertex(2)->info();
  const Vec2& pa = points[static_cast<std::size_t>(a)];
  const Vec2& pb = points[static_cast<std::size_t>(b)];
  const Vec2& pc = points[static_cast<std::size_t>(c)];
  const double ux = pb.x() - pa.x(), uy = pb.y() - pa.y();  // a -> b
  const double vx = pc.x() - pa.x(), vy = pc.y() - pa.y();  // a -> c
  const double wx = pc.x() - pb.x(), wy = pc.y() - pb.y();  // b -> c
  const double lab2 = ux * ux + uy * uy, lac2 = vx * vx + vy * vy, lbc2 = wx * wx + wy * wy;
  if (std::min({lab2, lac2, lbc2}) < in.tol2) {
    if (lab2 < in.tol2) throw_near_duplicate(a, b, points, in.where);
    if (lac2 < in.tol2) throw_near_duplicate(a, c, points, in.where);
    throw_near_duplicate(b, c, points, in.where);
  }
  const double cr = ux * vy - uy * vx;  // 2 * area
  const double he =
      (h[static_cast<std::size_t>(a)] + h[static_cast<std::size_t>(b)] + h[static_cast<std::size_t>(c)]) * (1.0 / 3.0);
  const double lll = std::sqrt(lab2) * std::sqrt(lac2) * std::sqrt(lbc2);
  const int walls = (kind[static_cast<std::size_t>(a)] != ParticleKind::Fluid) +
                    (kind[static_cast<std::size_t>(b)] != ParticleKind::Fluid) +
                    (kind[static_cast<std::size_t>(c)] != ParticleKind::Fluid);
  return {a, b, c, lab2, lac2, lbc2, cr, he, lll, walls};
}

/// Whether an element outside the advected domain (centroid `centroid`) joins the domain.
bool accept_contact(const RemeshInput& in, const FaceGeometry& g, const Vec2& centroid) {
  const RemeshSettings& settings = in.settings;
  const PreviousDomain* previous = in.previous;
  const auto& points = in.points;
  const auto& kind = in.kind;
  const auto [a, b, c, lab2, lac2, lbc2, cr, he, lll, walls] = g;
  // Outside the advected domain: a new contact (surfaces meeting, a surface reaching a wall), never
  // an element leaning on two boundary particles (the meniscus element of a dry wall), nor the fill of
  // a dent of one surface (an element with two edges on the previous boundary: consecutive surface
  // particles), nor an element reaching a dry wall or ghost particle (one the previous mesh did not
  // use) from fluid particles all farther than wetting_distance h_e from it (a dry wall is wetted by
  // fluid that reaches it, not by a surface particle passing at a spacing's distance).
  const double band = settings.level_set_band * he;
  const int on_boundary =
      previous->is_boundary_edge(a, b) + previous->is_boundary_edge(b, c) + previous->is_boundary_edge(c, a);
  bool reaches = true;
  const Index ids[3] = {a, b, c};
  for (int k = 0; k < 3; ++k) {
    const auto w = static_cast<std::size_t>(ids[k]);
    if (kind[w] == ParticleKind::Fluid || previous->meshed(ids[k])) continue;
    double nearest = std::numeric_limits<double>::infinity();
    for (int m = 0; m < 3; ++m) {
      const auto f = static_cast<std::size_t>(ids[m]);
      if (kind[f] == ParticleKind::Fluid) nearest = std::min(nearest, (points[f] - points[w]).norm());
    }
    reaches = reaches && nearest <= settings.wetting_distance * he;
  }
  // Two fluid surfaces meeting: the gap the element closes is its smallest height, 2A / l_max
  // (contact_gap). A surface reaching a wall or ghost particle is wetting_distance's concern.
  const bool gap_ok = walls > 0 || !(settings.contact_gap > 0) ||
                      cr <= settings.contact_gap * he * std::sqrt(std::max({lab2, lac2, lbc2}));
  return gap_ok && walls <= 1 && on_boundary < 2 && reaches &&
         (settings.detection == DomainDetection::LevelSet ? previous->boundary_distance(centroid, band) < band
                                                          : lll <= 2.0 * cr * settings.alpha * he);
}

/// The domain detection's verdict on a face (before the removal of wall/ghost-only elements).
enum class Verdict : std::uint8_t { RemovedAlpha, Separated, Accepted, AddedOutside };

/// The separation test of an element inside the previous domain: a sliver beyond separation_alpha h_e (R > that) is
/// a film tearing. An element leaning on a wall along an edge between two particles on it, whose third particle was
/// not on the previous free surface, is water against the wall: it cannot tear along the wall, and its flatness
/// (R grows without bound as the third particle nears the wall or the wall's particles spread along it) is not a
/// tear. It separates only when one of its two other edges is longer than separation_alpha h_e (the third particle
/// has left the wall); otherwise a confined flow would open a free surface with p = 0 inside its water.
bool separated(const RemeshInput& in, const FaceGeometry& g) {
  const double s = in.settings.separation_alpha * g.he;
  if (!in.on_previous_surface.empty()) {
    const std::vector<std::uint8_t>& on_wall = *in.settings.on_wall;
    const Index ids[3] = {g.a, g.b, g.c};
    const double opposite2[3] = {g.lbc2, g.lac2, g.lab2};  // the edge opposite a, b, c
    for (int k = 0; k < 3; ++k) {
      const auto i = static_cast<std::size_t>(ids[(k + 1) % 3]), j = static_cast<std::size_t>(ids[(k + 2) % 3]);
      if (!on_wall[i] || !on_wall[j]) continue;
      if (in.settings.along_wall && !in.settings.along_wall((in.points[i] + in.points[j]) * 0.5)) continue;
      if (in.on_previous_surface[static_cast<std::size_t>(ids[k])]) break;
      return std::max(opposite2[(k + 1) % 3], opposite2[(k + 2) % 3]) > s * s;
    }
  }
  return g.lll > 2.0 * g.cr * s;
}

/// The alpha test (or, with the previous domain, the separation test inside it and accept_contact outside).
Verdict detect(const RemeshInput& in, const FaceGeometry& g) {
  const auto& points = in.points;
  // Flat to round-off (three particles on one inclined wall, collinear up to the last bits of their
  // coordinates): never fluid, and not a separation either (it would be counted as one at each step).
  if (!(g.cr > 1e-12 * std::max({g.lab2, g.lac2, g.lbc2}))) return Verdict::RemovedAlpha;
  // R = l_ab l_ac l_bc / (4 A) <= alpha h_e  <=>  l_ab l_ac l_bc <= 2 cr alpha h_e (for cr > 0)
  if (in.previous == nullptr)
    return g.lll > 2.0 * g.cr * in.settings.alpha * g.he ? Verdict::RemovedAlpha : Verdict::Accepted;
  const Vec2& pa = points[static_cast<std::size_t>(g.a)];
  const Vec2& pb = points[static_cast<std::size_t>(g.b)];
  const Vec2& pc = points[static_cast<std::size_t>(g.c)];
  const Vec2 centroid = (pa + pb + pc) * (1.0 / 3.0);
  if (in.previous->contains(centroid)) return separated(in, g) ? Verdict::Separated : Verdict::Accepted;
  return accept_contact(in, g, centroid) ? Verdict::AddedOutside : Verdict::RemovedAlpha;
}

/// Pass 1: each finite face is kept (info kKept; with kReported too when it is this call's, then appended to
/// result.triangles) or not (info 0); the reported kept area (twice it, Neumaier-compensated) and the counts of
/// result. An element failing both the alpha test and the
/// wall/ghost-only test counts as removed by the alpha test.
void keep_faces(const RemeshInput& in, DT& dt, const Reported& reported, RemeshResult& result) {
  result.triangles.reserve(dt.number_of_faces());
  std::uint8_t* connected = result.connected.data();
  double area2 = 0.0, area2_comp = 0.0;  // twice the kept area, Neumaier-compensated sum
  int removed_alpha = 0, removed_boundary = 0, added = 0, separated = 0;
  for (auto f : dt.finite_face_handles()) {
    const FaceGeometry g = face_geometry(in, f);
    const Index a = g.a, b = g.b, c = g.c;
    // Another part's face is classified too (its flag is read by the free-surface pass) but not reported.
    const bool mine = reported.face(a, b, c);
    f->info() = 0;
    if (mine && g.walls == 3 && g.cr > 1e-12 * std::max({g.lab2, g.lac2, g.lbc2}))
      result.boundary_only.push_back({a, b, c});
    const Verdict verdict = detect(in, g);
    if (verdict == Verdict::RemovedAlpha) {
      removed_alpha += mine;
      continue;
    }
    if (verdict == Verdict::Separated) {
      if (mine) {
        ++separated;
        result.separated.push_back({a, b, c});
      }
      continue;
    }
    if (verdict == Verdict::AddedOutside && mine) {
      ++added;
      result.added_elements.push_back(static_cast<Index>(result.triangles.size()));
    }
    if (g.walls == 3) {
      removed_boundary += mine;
      continue;
    }
    f->info() = mine ? kKept | kReported : kKept;
    if (!mine) continue;
    result.triangles.push_back({a, b, c});
    connected[a] = connected[b] = connected[c] = 1;
    const double cr = g.cr;
    const double t = area2 + cr;
    area2_comp += std::abs(area2) >= cr ? (area2 - t) + cr : (cr - t) + area2;
    area2 = t;
  }
  result.area = 0.5 * (area2 + area2_comp);
  result.removed_alpha = removed_alpha;
  result.removed_boundary_only = removed_boundary;
  result.added_outside = added;
  result.separated_inside = separated;
}

/// Pass 2: an edge of a kept face is used by exactly one kept element iff the face across it (possibly
/// infinite) is not kept; its fluid particles are free surface. Every face's flag has been set (keep_faces,
/// and the infinite faces cleared before). Only the reported faces mark their particles.
void mark_free_surface(const RemeshInput& in, const DT& dt, RemeshResult& result) {
  std::uint8_t* fs = result.free_surface.data();
  for (auto f : dt.all_face_handles()) {
    if (!(f->info() & kReported)) continue;
    for (int i = 0; i < 3; ++i) {
      if (f->neighbor(i)->info() & kKept) continue;
      const Index p = f->vertex(DT::ccw(i))->info(), q = f->vertex(DT::cw(i))->info();
      if (in.kind[static_cast<std::size_t>(p)] == ParticleKind::Fluid) fs[p] = 1;
      if (in.kind[static_cast<std::size_t>(q)] == ParticleKind::Fluid) fs[q] = 1;
    }
  }
}

/// The stages after the triangulation: the previous domain's edges flipped back in, the domain detection on every
/// face and the free surface; the faces and counts of `reported` into result.
void triangulated(const RemeshInput& in, DT& dt, const Reported& reported, RemeshResult& result) {
  const std::size_t n = in.points.size();
  if (dt.dimension() < 2) {
    check_edges_1d(dt, in.points, in.tol2, in.where);
    return;
  }
  // The previous domain's boundary edges, and with keep_edges_angle its interior ones, flipped back in.
  if (in.previous != nullptr) {
    restore_boundary_edges(dt, *in.previous, n, reported, result.restored_edges, result.lost_edges);
    if (in.settings.keep_edges_angle > 0 && !in.previous->edges().empty())
      result.kept_edges = keep_previous_edges(dt, *in.previous, n, in.points, in.settings.keep_edges_angle, reported);
  }
  // The free-surface pass reads the flag of every neighbour, including the infinite faces.
  {
    auto fc = dt.incident_faces(dt.infinite_vertex());
    const auto done = fc;
    do fc->info() = 0;
    while (++fc != done);
  }
  keep_faces(in, dt, reported, result);
  mark_free_surface(in, dt, result);
}

}  // namespace

RemeshResult remesh(const std::vector<Vec2>& points, const std::vector<ParticleKind>& kind,
                    const std::vector<double>& h, const RemeshSettings& settings) {
  RemeshInput in{.points = points, .kind = kind, .h = h, .settings = settings};
  check_remesh_input(in);
  const std::size_t n = points.size();
  RemeshResult result;
  result.free_surface.assign(n, 0);
  result.connected.assign(n, 0);
  if (n < 3) return result;

  DT dt;
  build(dt, points, in.where);
  triangulated(in, dt, Reported{}, result);
  return result;
}

RemeshResult remesh_part(const std::vector<Vec2>& points, const std::vector<ParticleKind>& kind,
                         const std::vector<double>& h, const RemeshSettings& settings, const SpacePartition& partition,
                         int part, double halo, Index* ghost_count) {
  RemeshInput in{.points = points, .kind = kind, .h = h, .settings = settings, .where = "remesh_part"};
  check_remesh_input(in);
  if (settings.detection == DomainDetection::LevelSet && in.previous != nullptr)
    fail(in.where, "the level-set detection adds elements of any size: it is not divided into parts");
  if (partition.owner().size() != points.size())
    fail(in.where, "the partition was made for " + std::to_string(partition.owner().size()) + " points, not " +
                       std::to_string(points.size()));
  if (part < 0 || part >= partition.parts()) fail(in.where, "part " + std::to_string(part) + " out of range");
  if (!(std::isfinite(halo) && halo > 0)) fail(in.where, "halo must be finite and > 0");
  const std::size_t n = points.size();
  RemeshResult result;
  result.free_surface.assign(n, 0);
  result.connected.assign(n, 0);
  if (n < 3) return result;
  const std::vector<Index> local = partition.local(points, part, halo, ghost_count);
  if (local.size() < 3) return result;
  DT dt;
  build(dt, points, in.where, &local);
  triangulated(in, dt, Reported{&partition, part, &points}, result);
  return result;
}

std::vector<std::array<Index, 3>> delaunay_triangles(const std::vector<Vec2>& points) {
  const char* where = "delaunay_triangles";
  const double tol2 = check_points(points, where);
  std::vector<std::array<Index, 3>> triangles;
  if (points.size() < 3) return triangles;
  DT dt;
  build(dt, points, where);
  if (dt.dimension() < 2) {
    check_edges_1d(dt, points, tol2, where);
    return triangles;
  }
  triangles.reserve(dt.number_of_faces());
  for (auto f : dt.finite_face_handles()) {
    const Index a = f->vertex(0)->info(), b = f->vertex(1)->info(), c = f->vertex(2)->info();
    const Vec2& pa = points[static_cast<std::size_t>(a)];
    const Vec2& pb = points[static_cast<std::size_t>(b)];
    const Vec2& pc = points[static_cast<std::size_t>(c)];
    if ((pb - pa).squaredNorm() < tol2) throw_near_duplicate(a, b, points, where);
    if ((pc - pa).squaredNorm() < tol2) throw_near_duplicate(a, c, points, where);
    if ((pc - pb).squaredNorm() < tol2) throw_near_duplicate(b, c, points, where);
    triangles.push_back({a, b, c});
  }
  return triangles;
}

}  // namespace lagfsi::meshing
