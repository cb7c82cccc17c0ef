// The particle size field of an adaptive fluid (size_field.hpp): its input and its evaluation.
#include "size_field.hpp"

#include <lagfsi/geometry2d.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <utility>

namespace lagfsi::fluid {

namespace {

const KeyTable kSizeUniformKeys("/bodies/*/size_field (fluid body, type uniform)",
                                "One particle size, the spacing h, everywhere (the default).",
                                {{"type", "uniform", "`uniform`."}});

const KeyTable kSizeAdaptiveKeys(
    "/bodies/*/size_field (fluid body, type adaptive)",
    "Particles sized by where the flow needs them: the spacing h at the free surface, the walls, the structures "
    "and the open boundaries, growing with the distance d from them as h + gradation d up to max_size; "
    "re-evaluated at every remesh, the particle management merging and inserting particles to follow it. Needs "
    "unstructured particles. `\"size_field\": \"adaptive\"` takes every "
    "default.",
    {{"type", "adaptive", "`adaptive`."},
     {"max_size", 0.0, "The largest size (m), in the bulk; default: 4 h.", kDerived},
     {"gradation", 0.25,
      "How fast the size grows with the distance from the surface and the walls (size per unit length: about the "
      "growth from one particle layer to the next), in (0, 1]."},
     {"strain_rate", 0.0,
      "A flow indicator: particles where the flow's strain rate sqrt(2 D:D) (1/s) is at or above this value are "
      "sized h, like the free surface (a shear layer, the flow into an opening); 0: none. A velocity over a length "
      "of the flow is its scale (e.g. sqrt(g H) / H)."},
     {"regions", Json::array(),
      "Refinement boxes (see /bodies/*/size_field/regions/* (fluid body)), each with its own size, graded outside "
      "it."}});

const KeyTable kSizeBoxKeys("/bodies/*/size_field/regions/* (fluid body)",
                            "A box where the particles are at most a given size.",
                            {{"type", "box", "`box`."},
                             {"min", nullptr, "Lower-left corner [x, y] (m)."},
                             {"max", nullptr, "Upper-right corner [x, y] (m)."},
                             {"size", nullptr, "The size (m) inside the box, at least the spacing h."},
                             {"from", 0.0, "Start of the time window (s)."},
                             {"to", 1e300, "End of the time window (s)."}});

}  // namespace

void SizeField::expand_shorthand(Json& body) {
  if (body.is_object() && body.contains("size_field") && body.at("size_field").is_string())
    body["size_field"] = Json{{"type", body.at("size_field")}};
}

void SizeField::read(Params body, double h) {
  h_min_ = h_max_ = h;
  strain_rate_ = 0;
  adaptive_ = false;
  boxes_.clear();
  if (!body.has("size_field")) return;
  Params s = body.at("size_field");
  if (!s.json().is_object() || !s.has("type")) s.fail("type", "required key is missing (uniform or adaptive)");
  if (s.choice("type", {"uniform", "adaptive"}) == "uniform") {
    s.validate(kSizeUniformKeys);
    return;
  }
  s.validate(kSizeAdaptiveKeys, {{"max_size", 4.0 * h}});
  adaptive_ = true;
  h_max_ = s.positive("max_size");
  if (h_max_ < h) s.fail("max_size", "must be at least the spacing (" + std::to_string(h) + ")");
  gradation_ = s.positive("gradation");
  strain_rate_ = s.number("strain_rate");
  if (!(strain_rate_ >= 0)) s.fail("strain_rate", "must be at least 0 (0: no flow indicator)");
  if (gradation_ > 1.0) s.fail("gradation", "must lie in (0, 1] (the size grows at most by one size per size)");
  Params regions = s.at("regions");
  for (size_t k = 0; k < regions.size(); ++k) {
    Params r = regions.at(k);
    r.validate(kSizeBoxKeys);  // "type" defaults to "box", the one kind of region
    r.choice("type", {"box"});
    Box b{r.vec2("min"), r.vec2("max"), r.positive("size"), r.number("from"), r.number("to")};
    if (!(b.hi.x() > b.lo.x() && b.hi.y() > b.lo.y())) r.fail("max", "must lie above and to the right of min");
    if (b.size < h) r.fail("size", "must be at least the spacing (" + std::to_string(h) + ")");
    if (!(b.to > b.from)) r.fail("to", "must be after from");
    boxes_.push_back(b);
  }
}

double SizeField::box_size(const Vec2& x, double t) const {
  double s = h_max_;
  for (const Box& b : boxes_) {
    if (t < b.from || t > b.to) continue;
    const Vec2 outside = (b.lo - x).cwiseMax(x - b.hi).cwiseMax(Vec2::Zero());  // 0 inside
    s = std::min(s, b.size + gradation_ * outside.norm());
  }
  return s;
}

double SizeField::at(const Vec2& x, double d, double t) const {
  if (!adaptive_) return h_min_;
  return std::max(h_min_, std::min({h_max_, h_min_ + gradation_ * std::max(d, 0.0), box_size(x, t)}));
}

std::function<double(const Vec2&)> SizeField::initial_size(std::vector<std::vector<Vec2>> loops) const {
  return [this, loops = std::move(loops)](const Vec2& x) {
    double d = std::numeric_limits<double>::max();
    for (const auto& loop : loops)
      for (size_t i = 0; i < loop.size(); ++i)
        d = std::min(d, segment_distance(x, loop[i], loop[(i + 1) % loop.size()]));
    return at(x, d, 0.0);
  };
}

std::function<double(const Vec2&)> SizeField::uniform_mesher_size() const {
  constexpr double kUniformMesherScale = 1.5;
  return [h = h_min_](const Vec2&) { return kUniformMesherScale * h; };
}

std::function<double(const Vec2&)> SizeField::mesher_size(std::function<double(const Vec2&)> size) const {
  constexpr double kMesherScale = 1.35;
  return [this, size = std::move(size)](const Vec2& x) { return std::max(h_min_, kMesherScale * size(x)); };
}

Index SizeField::mark_straining(const std::vector<Vec2>& pts, const std::vector<Vec2>& v,
                                const std::vector<std::array<Index, 3>>& tri, std::vector<char>& source) const {
  if (!adaptive_ || !(strain_rate_ > 0)) return 0;
  const size_t n = pts.size();
  std::vector<double> sum(n, 0.0), area(n, 0.0);
  for (const auto& e : tri) {
    // The P1 velocity gradient L = [v1 - v0, v2 - v0] [x1 - x0, x2 - x0]^-1 of the element.
    Mat2 dx, dv;
    dx << pts[e[1]] - pts[e[0]], pts[e[2]] - pts[e[0]];
    dv << v[e[1]] - v[e[0]], v[e[2]] - v[e[0]];
    const double a = 0.5 * std::abs(dx.determinant());
    if (!(a > 0)) continue;
    const Mat2 grad = dv * dx.inverse();
    const Mat2 d = 0.5 * (grad + grad.transpose());
    const double gamma = std::sqrt(2.0 * d.squaredNorm());
    for (Index i : e) {
      sum[i] += a * gamma;
      area[i] += a;
    }
  }
  Index marked = 0;
  for (size_t i = 0; i < n; ++i)
    if (area[i] > 0 && sum[i] >= strain_rate_ * area[i] && !source[i]) {
      source[i] = 1;
      ++marked;
    }
  return marked;
}

void SizeField::targets(const std::vector<Vec2>& pts, const std::vector<std::array<Index, 3>>& tri,
                        const std::vector<char>& source, double t, std::vector<double>& h) const {
  const auto n = static_cast<Index>(pts.size());
  h.assign(static_cast<size_t>(n), h_min_);
  if (!adaptive_) return;
  // The mesh's edges as adjacency lists (compressed rows; each edge twice, duplicates harmless).
  std::vector<Index> start(static_cast<size_t>(n) + 1, 0), used(static_cast<size_t>(n), 0);
  for (const auto& e : tri)
    for (int k = 0; k < 3; ++k) {
      start[static_cast<size_t>(e[k]) + 1] += 2;
      used[static_cast<size_t>(e[k])] = 1;
    }
  for (Index i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<Index> adj(static_cast<size_t>(start[n])), fill(start.begin(), start.end() - 1);
  for (const auto& e : tri)
    for (int k = 0; k < 3; ++k) {
      const Index a = e[k], b = e[(k + 1) % 3], c = e[(k + 2) % 3];
      adj[fill[a]++] = b;
      adj[fill[a]++] = c;
    }
  // Sources: the features' particles (h_min) and every particle's own box size (h_max outside the boxes); each
  // particle then takes the smallest base + g |x - x_origin| over the origins reached through the edges.
  std::vector<double> base(static_cast<size_t>(n));
  std::vector<Index> origin(static_cast<size_t>(n));
  using Item = std::pair<double, Index>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (Index i = 0; i < n; ++i) {
    base[i] = source[i] || !used[i] ? h_min_ : std::max(h_min_, box_size(pts[i], t));
    h[i] = base[i];
    origin[i] = i;
    queue.emplace(h[i], i);
  }
  while (!queue.empty()) {
    const auto [value, i] = queue.top();
    queue.pop();
    if (value > h[i]) continue;  // a stale entry
    const Index o = origin[i];
    for (Index k = start[i]; k < start[i + 1]; ++k) {
      const Index j = adj[k];
      const double candidate = base[o] + gradation_ * (pts[j] - pts[o]).norm();
      if (candidate < h[j]) {
        h[j] = candidate;
        origin[j] = o;
        queue.emplace(candidate, j);
      }
    }
  }
  for (double& s : h) s = std::min(std::max(s, h_min_), h_max_);
}

}  // namespace lagfsi::fluid
