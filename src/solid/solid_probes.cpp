// Probes of a solid or shell body (solid_model_impl.hpp): displacement or position at a point, reaction
// on selected nodes, energies.
#include "solid_model_impl.hpp"

namespace lagfsi::solid {

namespace {

const KeyTable kDisplacementProbeKeys(
    "/probes/* (solid or shell body, type displacement or position)",
    "The displacement (m) or the current position (m) of a material point.",
    probe_keys({"displacement", "position"},
               {{"at", nullptr, "The point's reference position [x, y] (m); inside the body (a shell: its section)."},
                {"component", "y", "x, y or magnitude."}}));

const KeyTable kReactionProbeKeys("/probes/* (solid or shell body, type reaction)",
                                  "The sum of the reaction forces (N) over held nodes.",
                                  probe_keys({"reaction"},
                                             {{"select", nullptr, "The nodes (see selection (type point) and others)."},
                                              {"component", "y", "x or y."}}));

const KeyTable kEnergyProbeKeys(
    "/probes/* (solid or shell body, type energy)", "An energy of the body (J).",
    probe_keys({"energy"},
               {{"kind", "total",
                 "kinetic, strain, external_work, interface_work, dissipated, total (kinetic + strain) or balance "
                 "(E(t) - E(0) - external work + dissipated: zero for an exact integrator)."}}));

class DisplacementProbe final : public Probe {
 public:
  DisplacementProbe(const SolidModel& m, std::string name, std::vector<std::pair<Index, double>> weights,
                    std::string comp, bool position)
      : m_(m), name_(std::move(name)), weights_(std::move(weights)), comp_(std::move(comp)), position_(position) {}
  std::vector<std::string> columns() const override { return {name_}; }
  std::vector<double> sample() const override;

 private:
  const SolidModel& m_;
  std::string name_;
  std::vector<std::pair<Index, double>> weights_;
  std::string comp_;
  bool position_;
};

class ReactionProbe final : public Probe {
 public:
  ReactionProbe(const SolidModel& m, std::string name, std::vector<Index> nodes, int comp)
      : m_(m), name_(std::move(name)), nodes_(std::move(nodes)), comp_(comp) {}
  std::vector<std::string> columns() const override { return {name_}; }
  std::vector<double> sample() const override;

 private:
  const SolidModel& m_;
  std::string name_;
  std::vector<Index> nodes_;
  int comp_;
};

class EnergyProbe final : public Probe {
 public:
  EnergyProbe(const SolidModel& m, std::string name, std::string kind)
      : m_(m), name_(std::move(name)), kind_(std::move(kind)) {}
  std::vector<std::string> columns() const override { return {name_}; }
  std::vector<double> sample() const override;

 private:
  const SolidModel& m_;
  std::string name_, kind_;
};

}  // namespace

std::unique_ptr<Probe> SolidModel::make_probe(Params p) {
  const std::string t = p.choice("type", {"displacement", "position", "reaction", "energy"});
  if (t == "displacement" || t == "position") {
    p.validate(kDisplacementProbeKeys);
    const std::string comp = p.choice("component", {"x", "y", "magnitude"});
    std::vector<std::pair<Index, double>> w;
    if (!body_->locate(p.vec2("at"), w)) p.fail("at", "the point is outside body '" + name_ + "'");
    return std::make_unique<DisplacementProbe>(*this, p.string("name"), std::move(w), comp, t == "position");
  }
  if (t == "reaction") {
    p.validate(kReactionProbeKeys);
    const int comp = p.choice("component", {"x", "y"}) == "x" ? 0 : 1;
    need_reaction_ = true;
    std::vector<Index> nodes;
    for (Index s : select_nodes(p.at("select"), body_->stations())) nodes.push_back(body_->station_node(s));
    return std::make_unique<ReactionProbe>(*this, p.string("name"), std::move(nodes), comp);
  }
  p.validate(kEnergyProbeKeys);
  return std::make_unique<EnergyProbe>(
      *this, p.string("name"),
      p.choice("kind", {"kinetic", "strain", "external_work", "interface_work", "dissipated", "total", "balance"}));
}

std::vector<double> DisplacementProbe::sample() const {
  const Vec& x = m_.state().x;
  const Vec& X = m_.body().reference_positions();
  Vec2 u = Vec2::Zero();
  for (const auto& [node, w] : weights_) {
    const Vec2 d = x.segment<2>(2 * node) - (position_ ? Vec2::Zero() : Vec2(X.segment<2>(2 * node)));
    u += w * d;
  }
  if (comp_ == "x") return {u.x()};
  if (comp_ == "y") return {u.y()};
  return {u.norm()};
}

std::vector<double> ReactionProbe::sample() const {
  const Vec& r = m_.reaction();
  double s = 0.0;
  if (r.size() == 0) return {0.0};
  for (Index n : nodes_) s += r[2 * n + comp_];
  return {s};
}

std::vector<double> EnergyProbe::sample() const {
  if (kind_ == "kinetic") return {m_.kinetic_energy()};
  if (kind_ == "strain") return {m_.strain_energy()};
  if (kind_ == "external_work") return {m_.external_work()};
  if (kind_ == "interface_work") return {m_.interface_work()};
  if (kind_ == "dissipated") return {m_.dissipated()};
  const double total = m_.kinetic_energy() + m_.strain_energy();
  if (kind_ == "total") return {total};
  // balance: E(t) - E(0) - W_ext + W_damp, zero for an exact integrator.
  return {total - m_.initial_energy() - m_.external_work() + m_.dissipated()};
}

}  // namespace lagfsi::solid
