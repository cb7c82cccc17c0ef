#include <lagfsi/case.hpp>
#include <lagfsi/meshing/primitives.hpp>

#include <cmath>
#include <numbers>

namespace lagfsi {

namespace {

const KeyTable kMeshKeys("mesh (triangles of a geometry)", "How a body's geometry is meshed into triangles.",
                         {{"size", nullptr, "Target element size (m)."},
                          {"order", 1, "Element order: 1, 2 or 3 (straight-sided triangles of 3, 6 or 10 nodes)."},
                          {"type", "unstructured",
                           "`unstructured` (Delaunay) or `structured` (a grid of triangles; rectangles only)."},
                          {"divisions", Json::array(), "Structured mesh: cells [nx, ny] (default []: from the size)."},
                          {"pattern", "crossed", "Structured mesh: how each cell is split: crossed, right or left."}});

const KeyTable kRectangleKeys("geometry (type rectangle)", "An axis-aligned rectangle.",
                              {{"type", "rectangle", "`rectangle`."},
                               {"origin", Json::array({0.0, 0.0}), "Lower-left corner [x, y] (m)."},
                               {"size", nullptr, "Width and height [w, h] (m), positive."}});

const KeyTable kPolygonKeys("geometry (type polygon)", "A polygon, possibly with holes.",
                            {{"type", "polygon", "`polygon`."},
                             {"points", nullptr, "Outline [[x, y], ...] (m), in order, not closed."},
                             {"holes", Json::array(), "Holes, each an outline [[x, y], ...] (m)."}});

const KeyTable kCircleCutKeys("geometry (type circle_cut)",
                              "A polygon minus a disc that cuts it (e.g. a flag clamped on a cylinder).",
                              {{"type", "circle_cut", "`circle_cut`."},
                               {"points", nullptr, "Outline of the polygon [[x, y], ...] (m)."},
                               {"centre", nullptr, "Centre of the disc [x, y] (m)."},
                               {"radius", nullptr, "Radius of the disc (m)."}});

const char* const kSelectionTolerance =
    "Distance (m) within which a node is selected; default: 1e-6 times the diagonal of the nodes' bounding box.";

const KeyTable kSelectPointKeys("selection (type point)", "The node nearest to a point.",
                                {{"type", "point", "`point`."},
                                 {"at", nullptr, "The point [x, y] (m)."},
                                 {"tolerance", 0.0, kSelectionTolerance, kDerived}});

const KeyTable kSelectSegmentKeys("selection (type segment)", "The nodes on a segment.",
                                  {{"type", "segment", "`segment`."},
                                   {"from", nullptr, "One end [x, y] (m)."},
                                   {"to", nullptr, "The other end [x, y] (m)."},
                                   {"tolerance", 0.0, kSelectionTolerance, kDerived}});

const KeyTable kSelectPolylineKeys(
    "selection (type polyline)",
    "The nodes on a polyline (e.g. the wet faces of a flag, without the arc it is clamped on).",
    {{"type", "polyline", "`polyline`."},
     {"points", nullptr,
      "Its vertices [[x, y], ...] (m), at least two, in order (open: the last is not joined to the first)."},
     {"tolerance", 0.0, kSelectionTolerance, kDerived}});

const KeyTable kSelectBoxKeys("selection (type box)", "The nodes in an axis-aligned box (its edges included).",
                              {{"type", "box", "`box`."},
                               {"min", nullptr, "Lower-left corner [x, y] (m)."},
                               {"max", nullptr, "Upper-right corner [x, y] (m)."}});

const KeyTable kSelectCircleKeys("selection (type circle)", "The nodes on a circle.",
                                 {{"type", "circle", "`circle`."},
                                  {"centre", nullptr, "Centre [x, y] (m)."},
                                  {"radius", nullptr, "Radius (m)."},
                                  {"tolerance", 0.0, kSelectionTolerance, kDerived}});

const KeyTable kSelectAllKeys("selection (type all)", "Every node.", {{"type", "all", "`all`."}});

/// Distance from p to the segment [a, b] (to a when the segment is a point).
double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * d)).norm();
}

double bbox_diagonal(const std::vector<Vec2>& pts) {
  if (pts.empty()) return 1.0;
  Vec2 lo = pts[0], hi = pts[0];
  for (const auto& p : pts) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return std::max((hi - lo).norm(), 1e-300);
}

/// Boundary of (polygon minus disc) for a disc that crosses the polygon boundary exactly twice.
std::vector<Vec2> circle_cut(const Params& g, const std::vector<Vec2>& poly, const Vec2& c, double r, double h) {
  const size_t n = poly.size();
  auto inside = [&](const Vec2& p) { return (p - c).norm() < r; };
  struct Crossing {
    size_t edge;
    double s;
    Vec2 p;
    bool entering;
  };
  std::vector<Crossing> cross;
  for (size_t i = 0; i < n; ++i) {
    const Vec2 a = poly[i], b = poly[(i + 1) % n], d = b - a;
    // |a + s d - c|^2 = r^2
    const double A = d.squaredNorm(), B = 2 * d.dot(a - c), C = (a - c).squaredNorm() - r * r;
    const double disc = B * B - 4 * A * C;
    if (disc <= 0) continue;
    const double sq = std::sqrt(disc);
    for (double s : {(-B - sq) / (2 * A), (-B + sq) / (2 * A)})
      if (s > 0 && s < 1) cross.push_back({i, s, a + s * d, inside(a + (s + 1e-9) * d)});
  }
  if (cross.size() != 2)
    g.fail("the circle must cut the polygon boundary in exactly two points (found " + std::to_string(cross.size()) +
           ")");
  std::sort(cross.begin(), cross.end(),
            [](const Crossing& x, const Crossing& y) { return x.edge != y.edge ? x.edge < y.edge : x.s < y.s; });
  const Crossing& enter = cross[0].entering ? cross[0] : cross[1];
  const Crossing& leave = cross[0].entering ? cross[1] : cross[0];
  // Walk from the exit point along the polygon (outside the disc) to the entry point, then along the arc
  // back to the exit point (the arc bulges into the polygon: clockwise around c for a CCW polygon).
  std::vector<Vec2> out{leave.p};
  size_t i = (leave.edge + 1) % n;
  for (size_t k = 0; k < n; ++k) {
    if (i == (enter.edge + 1) % n && k > 0) break;
    if (!inside(poly[i])) out.push_back(poly[i]);
    if (i == enter.edge) break;
    i = (i + 1) % n;
  }
  out.push_back(enter.p);
  const double a0 = std::atan2(enter.p.y() - c.y(), enter.p.x() - c.x());
  double a1 = std::atan2(leave.p.y() - c.y(), leave.p.x() - c.x());
  // Go the way whose mid-point is inside the polygon: try both senses.
  auto mid_inside_poly = [&](double from, double to) {
    const double am = 0.5 * (from + to);
    const Vec2 m = c + r * Vec2(std::cos(am), std::sin(am));
    bool in = false;  // even-odd rule
    for (size_t j = 0, k = n - 1; j < n; k = j++)
      if ((poly[j].y() > m.y()) != (poly[k].y() > m.y()) &&
          m.x() < (poly[k].x() - poly[j].x()) * (m.y() - poly[j].y()) / (poly[k].y() - poly[j].y()) + poly[j].x())
        in = !in;
    return in;
  };
  double a1_ccw = a1, a1_cw = a1;
  while (a1_ccw <= a0) a1_ccw += 2 * std::numbers::pi;
  while (a1_cw >= a0) a1_cw -= 2 * std::numbers::pi;
  a1 = mid_inside_poly(a0, a1_ccw) ? a1_ccw : a1_cw;
  auto arc = meshing::arc_points(c, r, a0, a1, h);
  for (size_t k = 1; k + 1 < arc.size(); ++k) out.push_back(arc[k]);
  return out;
}

}  // namespace

std::vector<Vec2> circle_cut_outline(Params g, double h) {
  return circle_cut(g, g.points("points"), g.vec2("centre"), g.positive("radius"), h);
}

std::vector<std::vector<Vec2>> geometry_loops(Params g, double h) {
  if (!g.json().is_object() || !g.has("type")) g.fail("type", "required key is missing");
  const std::string type = g.choice("type", {"rectangle", "polygon", "circle_cut"});
  std::vector<std::vector<Vec2>> loops;
  g.validate(type == "rectangle" ? kRectangleKeys : type == "polygon" ? kPolygonKeys : kCircleCutKeys);
  if (type == "rectangle") {
    const Vec2 o = g.has("origin") ? g.vec2("origin") : Vec2::Zero(), s = g.vec2("size");
    loops.push_back({o, o + Vec2(s.x(), 0), o + s, o + Vec2(0, s.y())});
  } else if (type == "polygon") {
    loops.push_back(g.points("points"));
    const Params holes = g.at("holes");
    for (size_t i = 0; i < holes.size(); ++i) {
      Params hp(Json{{"p", holes.json()[i]}}, g.file(), holes.path() + "/" + std::to_string(i));
      loops.push_back(hp.points("p"));
    }
  } else {
    loops.push_back(circle_cut_outline(g, h));
  }
  return loops;
}

namespace {
double g_max_mesh_nodes = 2e6;
}

double max_mesh_nodes() { return g_max_mesh_nodes; }
void set_max_mesh_nodes(double nodes) { g_max_mesh_nodes = nodes; }

TriMesh build_mesh(Params g, Params m, const std::function<double(const Vec2&)>& size) {
  if (!g.json().is_object() || !g.has("type")) g.fail("type", "required key is missing");
  const std::string type = g.choice("type", {"rectangle", "polygon", "circle_cut"});
  m.validate(kMeshKeys);
  const double h = m.positive("size");
  const int order = m.integer("order", 1);
  if (order > 3) m.fail("order", "must be 1, 2 or 3");
  const std::string mtype = m.choice("type", {"unstructured", "structured"});
  // At most max_mesh_nodes() nodes once elevated (an element of order p brings about p^2/2 nodes).
  const double max_elements = g_max_mesh_nodes / std::max(0.5, 0.5 * order * order);
  auto too_many = [&](double elements) {
    m.fail("size", "about " + std::to_string(static_cast<long long>(elements)) + " elements, more than the " +
                       std::to_string(static_cast<long long>(max_elements)) + " of " +
                       std::to_string(static_cast<long long>(g_max_mesh_nodes)) + " nodes at order " +
                       std::to_string(order) + " (--max-nodes raises the limit)");
  };
  TriMesh linear;
  try {
    if (type == "rectangle") {
      g.validate(kRectangleKeys);
      const Vec2 o = g.vec2("origin"), s = g.vec2("size");
      if (!(s.x() > 0 && s.y() > 0)) g.fail("size", "width and height must be positive");
      if (mtype == "structured") {
        // Cell counts in double until they are checked: s / h, or a given division, can exceed int's range.
        double fx = std::ceil(s.x() / h - 1e-9), fy = std::ceil(s.y() / h - 1e-9);
        const auto div = m.json().at("divisions");
        if (!div.empty()) {
          if (!div.is_array() || div.size() != 2 || !div[0].is_number_integer() || !div[1].is_number_integer() ||
              div[0].get<double>() < 1 || div[1].get<double>() < 1)
            m.fail("divisions", "expected [nx, ny], two positive integers");
          fx = div[0].get<double>();
          fy = div[1].get<double>();
        }
        if (!(2.0 * fx * fy <= max_elements)) too_many(2.0 * fx * fy);
        const int nx = static_cast<int>(fx), ny = static_cast<int>(fy);
        linear = meshing::mesh_rectangle_structured(o.x(), o.y(), o.x() + s.x(), o.y() + s.y(), nx, ny,
                                                    m.choice("pattern", {"crossed", "right", "left"}));
      } else {
        meshing::PolygonRegion r;
        r.outer = {o, o + Vec2(s.x(), 0), o + s, o + Vec2(0, s.y())};
        linear = meshing::mesh_polygon(r, h, max_elements, size);
      }
    } else {
      if (mtype == "structured") m.fail("type", "a structured mesh needs a rectangle geometry");
      if (type == "polygon") {
        g.validate(kPolygonKeys);
        meshing::PolygonRegion r;
        r.outer = g.points("points");
        const Params holes = g.at("holes");
        for (size_t i = 0; i < holes.size(); ++i) {
          Params hp(Json{{"p", holes.json()[i]}}, g.file(), holes.path() + "/" + std::to_string(i));
          r.holes.push_back(hp.points("p"));
        }
        linear = meshing::mesh_polygon(r, h, max_elements, size);
      } else {
        g.validate(kCircleCutKeys);
        meshing::PolygonRegion r;
        r.outer = circle_cut(g, g.points("points"), g.vec2("centre"), g.positive("radius"), h);
        linear = meshing::mesh_polygon(r, h, max_elements, size);
      }
    }
  } catch (const meshing::MeshTooLarge& e) {  // the limit is ours (max_mesh_nodes): say how to raise it
    g.fail(std::string("cannot mesh this geometry: ") + e.what() + " (--max-nodes raises the limit)");
  } catch (const std::invalid_argument& e) {
    g.fail(std::string("cannot mesh this geometry: ") + e.what());
  }
  return order == 1 ? linear : meshing::elevate(linear, order);
}

std::vector<Index> select_nodes(Params s, const std::vector<Vec2>& nodes) {
  if (!s.json().is_object() || !s.has("type")) s.fail("type", "required key is missing");
  const std::string type = s.choice("type", {"point", "segment", "polyline", "box", "circle", "all"});
  const double L = bbox_diagonal(nodes);
  std::vector<Index> out;
  if (type == "point") {
    s.validate(kSelectPointKeys, {{"tolerance", 1e-6 * L}});
    const Vec2 p = s.vec2("at");
    const double tol = s.positive("tolerance");
    Index best = -1;
    double dbest = 1e300;
    for (Index i = 0; i < static_cast<Index>(nodes.size()); ++i) {
      const double d = (nodes[i] - p).norm();
      if (d < dbest) {
        dbest = d;
        best = i;
      }
    }
    if (best < 0 || dbest > tol)
      s.fail("at",
             "no node within " + std::to_string(tol) + " of the point (nearest at " + std::to_string(dbest) + ")");
    out.push_back(best);
  } else if (type == "segment") {
    s.validate(kSelectSegmentKeys, {{"tolerance", 1e-6 * L}});
    const Vec2 a = s.vec2("from"), b = s.vec2("to");
    const double tol = s.positive("tolerance");
    for (Index i = 0; i < static_cast<Index>(nodes.size()); ++i)
      if (distance_to_segment(nodes[i], a, b) <= tol) out.push_back(i);
  } else if (type == "polyline") {
    s.validate(kSelectPolylineKeys, {{"tolerance", 1e-6 * L}});
    const std::vector<Vec2> v = s.points("points");
    if (v.size() < 2) s.fail("points", "a polyline needs at least two points");
    const double tol = s.positive("tolerance");
    for (Index i = 0; i < static_cast<Index>(nodes.size()); ++i)
      for (size_t k = 0; k + 1 < v.size(); ++k)
        if (distance_to_segment(nodes[i], v[k], v[k + 1]) <= tol) {
          out.push_back(i);
          break;
        }
  } else if (type == "box") {
    s.validate(kSelectBoxKeys);
    const Vec2 lo = s.vec2("min"), hi = s.vec2("max");
    for (Index i = 0; i < static_cast<Index>(nodes.size()); ++i)
      if ((nodes[i].array() >= lo.array()).all() && (nodes[i].array() <= hi.array()).all()) out.push_back(i);
  } else if (type == "circle") {
    s.validate(kSelectCircleKeys, {{"tolerance", 1e-6 * L}});
    const Vec2 c = s.vec2("centre");
    const double r = s.positive("radius"), tol = s.positive("tolerance");
    for (Index i = 0; i < static_cast<Index>(nodes.size()); ++i)
      if (std::abs((nodes[i] - c).norm() - r) <= tol) out.push_back(i);
  } else {
    s.validate(kSelectAllKeys);
    for (Index i = 0; i < static_cast<Index>(nodes.size()); ++i) out.push_back(i);
  }
  if (out.empty()) s.fail("the selection contains no node");
  return out;
}

}  // namespace lagfsi
