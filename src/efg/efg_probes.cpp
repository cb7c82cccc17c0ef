// EFG probes (probes.csv columns): load factor, total applied load (lambda times the reference load's component,
// times `scale`), displacement of a node (U = f(V), or its parameter V), reaction of a node selection (internal force
// minus applied load, summed), largest damage. See src/efg/include/lagfsi/efg/efg_model.hpp.
#include <lagfsi/efg/efg_model.hpp>
#include <lagfsi/error.hpp>

#include <algorithm>
#include <functional>

namespace lagfsi::efg {

namespace {

const KeyTable kEfgLoadFactorProbeKeys("/probes/* (efg body, type load_factor)", "The load factor lambda.",
                                       probe_keys({"load_factor"}, {}));

const KeyTable kEfgDamageProbeKeys("/probes/* (efg body, type damage_max)", "The largest damage (0-1) of the body.",
                                   probe_keys({"damage_max"}, {}));

const KeyTable kEfgLoadProbeKeys("/probes/* (efg body, type load)",
                                 "The total applied load (N): lambda times the reference load.",
                                 probe_keys({"load"},
                                            {{"component", "y", "x or y."}, {"scale", 1.0, "Factor applied to it."}}));

const KeyTable kEfgStressProbeKeys("/probes/* (efg body, type stress)",
                                   "The elastic stress (Pa) at a node, averaged over the cells around it.",
                                   probe_keys({"stress"}, {{"at", nullptr, "The node [x, y] (m)."},
                                                           {"component", "xx", "xx, yy or xy."}}));

const KeyTable kEfgDisplacementProbeKeys(
    "/probes/* (efg body, type displacement)", "The displacement (m) at a node, or its MLS parameter.",
    probe_keys({"displacement"}, {{"at", nullptr, "The node [x, y] (m)."},
                                  {"component", "y", "x or y."},
                                  {"value", "displacement", "displacement or parameter (the nodal MLS parameter)."}}));

const KeyTable kEfgReactionProbeKeys("/probes/* (efg body, type reaction)", "The sum of the reactions (N) over nodes.",
                                     probe_keys({"reaction"}, {{"select", nullptr,
                                                                "The nodes (see selection (type point) and others)."},
                                                               {"component", "y", "x or y."}}));
class FnProbe final : public Probe {
 public:
  FnProbe(std::string name, std::function<double()> f) : name_(std::move(name)), f_(std::move(f)) {}
  std::vector<std::string> columns() const override { return {name_}; }
  std::vector<double> sample() const override { return {f_()}; }

 private:
  std::string name_;
  std::function<double()> f_;
};
}  // namespace

std::unique_ptr<Probe> EfgModel::make_probe(Params p) {
  const std::string t = p.choice("type", {"load_factor", "load", "displacement", "reaction", "damage_max", "stress"});
  const std::string name = p.identifier("name");
  if (t == "load_factor") {
    p.validate(kEfgLoadFactorProbeKeys);
    return std::make_unique<FnProbe>(name, [this] { return lambda0_; });
  }
  if (t == "damage_max") {
    p.validate(kEfgDamageProbeKeys);
    return std::make_unique<FnProbe>(name, [this] { return summary()["damage_max"].get<double>(); });
  }
  if (t == "load") {
    p.validate(kEfgLoadProbeKeys);
    const int comp = p.choice("component", {"x", "y"}) == "x" ? 0 : 1;
    const double scale = p.number("scale");
    double total = 0;
    for (Index n = 0; n < mesh_.num_nodes(); ++n) total += Ptr_[2 * n + comp];
    return std::make_unique<FnProbe>(name, [this, total, scale] { return scale * lambda0_ * total; });
  }
  if (t == "stress") {
    // Elastic stress D0 B v at a node, averaged over the cells around it (each evaluates its own functions).
    p.validate(kEfgStressProbeKeys);
    Json sel = {{"type", "point"}, {"at", p.json()["at"]}};
    Params sp(sel, p.file(), p.path());  // a point selection whose "at" is the probe's: errors name /probes/i/at
    const Index n = select_nodes(sp, mesh_.nodes).front();
    const std::vector<std::string> comps = {"xx", "yy", "xy"};
    const std::string cs = p.choice("component", comps);
    const int comp = static_cast<int>(std::find(comps.begin(), comps.end(), cs) - comps.begin());
    std::vector<ShapeValues> shapes;
    for (Index c = 0; c < mesh_.num_cells(); ++c)
      for (int a = 0; a < mesh_.nodes_per_cell(); ++a)
        if (mesh_.cell_node(c, a) == n) {
          shapes.emplace_back();
          double xi, eta;
          cell_node_natural(a, xi, eta);
          try {
            shape_at(c, xi, eta, shapes.back(), true);
          } catch (const SolverError& e) {
            p.fail("at", std::string("the shape functions cannot be differentiated at this node: ") + e.what());
          }
        }
    return std::make_unique<FnProbe>(name, [this, shapes, comp] {
      double s = 0;
      for (const auto& sh : shapes) {
        Vec3 e = Vec3::Zero();
        for (size_t k = 0; k < sh.nodes.size(); ++k) {
          const double vx = x0_[2 * sh.nodes[k]], vy = x0_[2 * sh.nodes[k] + 1];
          e += Vec3(sh.Nx[k] * vx, sh.Ny[k] * vy, sh.Ny[k] * vx + sh.Nx[k] * vy);
        }
        s += (material_->elastic() * e)[comp];
      }
      return s / static_cast<double>(shapes.size());
    });
  }
  if (t == "displacement") {
    p.validate(kEfgDisplacementProbeKeys);
    Json sel = {{"type", "point"}, {"at", p.json()["at"]}};
    Params sp(sel, p.file(), p.path());  // a point selection whose "at" is the probe's: errors name /probes/i/at
    const Index n = select_nodes(sp, mesh_.nodes).front();
    const int comp = p.choice("component", {"x", "y"}) == "x" ? 0 : 1;
    if (p.choice("value", {"displacement", "parameter"}) == "parameter")
      return std::make_unique<FnProbe>(name, [this, n, comp] { return x0_[2 * n + comp]; });
    return std::make_unique<FnProbe>(name, [this, n, comp] {
      double u = 0;
      for (const auto& [j, v] : node_eval_[n]) u += v * x0_[2 * j + comp];
      return u;
    });
  }
  p.validate(kEfgReactionProbeKeys);
  const auto nodes = select_nodes(p.at("select"), mesh_.nodes);
  const int comp = p.choice("component", {"x", "y"}) == "x" ? 0 : 1;
  return std::make_unique<FnProbe>(name, [this, nodes, comp] {
    const Vec r = reactions();
    double s = 0;
    for (Index n : nodes) s += r[2 * n + comp];
    return s;
  });
}

}  // namespace lagfsi::efg
