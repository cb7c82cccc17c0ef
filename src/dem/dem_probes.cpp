// Probes of a DEM body (src/dem/include/lagfsi/dem/dem_model.hpp), columns of probes.csv sampled after each driver
// step:
//  - {"type": "energy", "kind": "kinetic" | "rotational" | "elastic" | "gravity" | "dissipated" | "blast_work" |
//    "balance"}: kinetic (translation + rotation), elastic (stored in the contacts), gravity (-sum m g.x),
//    dissipated (dashpots and sliding, accumulated), blast work (accumulated), balance = kinetic + elastic +
//    gravity + dissipated - blast work - (the same at t = 0): ~0 up to the O(dt) error of the bookkeeping;
//  - {"type": "contacts"}: the number of contacts (disc-disc and disc-wall) with a non-zero force;
//  - {"type": "max_contact_force"}: the largest contact force |F|;
//  - {"type": "disc", "id": k, "quantity": "x" | "y" | "vx" | "vy" | "omega" | "theta"}: one disc (its id is its
//    place in generation order);
//  - {"type": "ke_near", "at": [x, y], "count": 6}: the mean kinetic energy of the `count` discs nearest `at` at
//    t = 0 (Sabatucci et al.'s probes at four depths), and a second column <name>_peak_time: the time of its
//    largest value so far;
//  - {"type": "front", "skip": k}: the largest x + r, ignoring the k farthest discs (strays rolling away);
//    {"type": "height", "x": x, "band": b}: the largest y + r of the discs
//    whose centre lies within b of x (default b = 2 r_max).
// Checkpoints: a ke_near probe keeps its discs and its peak (serialize); the others keep nothing.
#include "dem_body.hpp"

#include <lagfsi/dem/dem_model.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>

namespace lagfsi::dem {

namespace {

const KeyTable kDemEnergyProbeKeys(
    "/probes/* (dem body, type energy)", "An energy of the body (J per m of depth).",
    probe_keys({"energy"},
               {{"kind", "kinetic",
                 "kinetic (translation + rotation), rotational, elastic (in the contacts), gravity, dissipated, "
                 "blast_work or balance (about 0)."}}));

const KeyTable kDemFrontProbeKeys("/probes/* (dem body, type front)", "The largest x + r (m) of the discs.",
                                  probe_keys({"front"},
                                             {{"skip", 0, "Ignore the this many farthest discs (strays)."}}));

const KeyTable kDemCountProbeKeys(
    "/probes/* (dem body, type contacts or max_contact_force)",
    "The number of contacts with a non-zero force, or the largest contact force (N per m).",
    probe_keys({"contacts", "max_contact_force"}, {}));

const KeyTable kDemDiscProbeKeys(
    "/probes/* (dem body, type disc)", "A quantity of one disc.",
    probe_keys({"disc"}, {{"id", nullptr, "The disc's place in generation order (from 0)."},
                          {"quantity", "y", "x, y (m), vx, vy (m/s), omega (rad/s) or theta (rad)."}}));

const KeyTable kDemKeNearProbeKeys(
    "/probes/* (dem body, type ke_near)",
    "The mean kinetic energy (J per m) of the discs nearest a point at t = 0, and a column <name>_peak_time.",
    probe_keys({"ke_near"}, {{"at", nullptr, "The point [x, y] (m)."}, {"count", 6, "How many discs."}}));

const KeyTable kDemHeightProbeKeys(
    "/probes/* (dem body, type height)", "The largest y + r (m) of the discs whose centre lies within a band of x.",
    probe_keys({"height"}, {{"x", nullptr, "x (m) of the line."},
                            {"band", 0.0, "Half-width (m) of the band; 0: twice the largest radius."}}));

}  // namespace

namespace {

class DemProbe final : public Probe {
 public:
  DemProbe(const DemModel& m, std::string name, std::string type, std::string quantity)
      : m_(m), name_(std::move(name)), type_(std::move(type)), q_(std::move(quantity)) {}
  std::vector<std::string> columns() const override {
    if (type_ == "ke_near") return {name_, name_ + "_peak_time"};
    return {name_};
  }
  std::vector<double> sample() const override;
  /// ke_near: the chosen discs (by id) and the peak so far.
  void serialize(StateArchive& ar) override {
    ar.section("dem probe " + name_);
    ar.io(chosen_, peak_, peak_time_);
  }

  Index id = -1;
  Vec2 at = Vec2::Zero();
  int count = 6;
  double x = 0, band = 0;
  int skip = 0;

 private:
  const DemModel& m_;
  std::string name_, type_, q_;
  mutable std::vector<Index> chosen_;
  mutable double peak_ = -1, peak_time_ = 0;
};

std::vector<double> DemProbe::sample() const {
  const DemBody& b = m_.body();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (type_ == "energy") {
    if (q_ == "kinetic") return {b.kinetic_energy()};
    if (q_ == "rotational") return {b.rotational_energy()};
    if (q_ == "elastic") return {b.elastic};
    if (q_ == "gravity") return {b.gravity_potential()};
    if (q_ == "dissipated") return {b.dissipated};
    if (q_ == "blast_work") return {b.blast_work};
    return {m_.energy_balance()};
  }
  if (type_ == "contacts") return {static_cast<double>(b.contact_count())};
  if (type_ == "max_contact_force") return {b.max_contact_force()};
  if (type_ == "disc") {
    const Index p = b.where[id];
    if (q_ == "x") return {b.state.x[3 * p]};
    if (q_ == "y") return {b.state.x[3 * p + 1]};
    if (q_ == "theta") return {b.state.x[3 * p + 2]};
    if (q_ == "vx") return {b.state.v[3 * p]};
    if (q_ == "vy") return {b.state.v[3 * p + 1]};
    return {b.state.v[3 * p + 2]};
  }
  if (type_ == "ke_near") {
    if (chosen_.empty()) {
      std::vector<Index> ids(b.size());
      std::iota(ids.begin(), ids.end(), 0);
      auto dist = [&](Index i) { return (b.position(b.where[i]) - at).squaredNorm(); };
      const size_t k = std::min<size_t>(count, ids.size());
      std::partial_sort(ids.begin(), ids.begin() + k, ids.end(),
                        [&](Index a, Index c) { return dist(a) < dist(c) || (dist(a) == dist(c) && a < c); });
      chosen_.assign(ids.begin(), ids.begin() + k);
    }
    double e = 0;
    for (Index i : chosen_) {
      const Index p = b.where[i];
      e += 0.5 * b.discs.mass[p] * b.velocity(p).squaredNorm();
      if (b.rotation) e += 0.5 * b.discs.inertia[p] * b.state.v[3 * p + 2] * b.state.v[3 * p + 2];
    }
    e /= chosen_.size();
    if (e > peak_) {
      peak_ = e;
      peak_time_ = b.state.t;
    }
    return {e, peak_time_};
  }
  if (type_ == "front") {
    std::vector<double> f(b.size());
    for (size_t p = 0; p < b.size(); ++p) f[p] = b.state.x[3 * p] + b.discs.radius[p];
    const size_t k = std::min<size_t>(skip, f.size() - 1);
    std::nth_element(f.begin(), f.begin() + k, f.end(), std::greater<double>());
    return {f[k]};
  }
  double best = -std::numeric_limits<double>::infinity();
  for (size_t p = 0; p < b.size(); ++p) {
    const Vec2 c = b.position(static_cast<Index>(p));
    if (type_ == "front")
      best = std::max(best, c.x() + b.discs.radius[p]);
    else if (std::abs(c.x() - x) <= band)
      best = std::max(best, c.y() + b.discs.radius[p]);
  }
  return {std::isfinite(best) ? best : nan};
}

}  // namespace

}  // namespace lagfsi::dem

namespace lagfsi::dem {

std::unique_ptr<Probe> DemModel::make_probe(Params p) {
  DemBody& b = *body_;
  const std::string t =
      p.choice("type", {"energy", "contacts", "max_contact_force", "disc", "ke_near", "front", "height"});
  const std::string name = p.identifier("name");
  if (t == "energy") {
    p.validate(kDemEnergyProbeKeys);
    const std::string k =
        p.choice("kind", {"kinetic", "rotational", "elastic", "gravity", "dissipated", "blast_work", "balance"});
    if (k == "elastic" || k == "dissipated" || k == "balance") b.track_energy = true;
    return std::make_unique<DemProbe>(*this, name, t, k);
  }
  if (t == "front") {
    p.validate(kDemFrontProbeKeys);
    auto probe = std::make_unique<DemProbe>(*this, name, t, "");
    probe->skip = p.integer("skip", 0);
    return probe;
  }
  if (t == "contacts" || t == "max_contact_force") {
    p.validate(kDemCountProbeKeys);
    return std::make_unique<DemProbe>(*this, name, t, "");
  }
  if (t == "disc") {
    p.validate(kDemDiscProbeKeys);
    auto probe =
        std::make_unique<DemProbe>(*this, name, t, p.choice("quantity", {"x", "y", "vx", "vy", "omega", "theta"}));
    probe->id = p.integer("id", 0);
    if (probe->id >= static_cast<Index>(b.size()))
      p.fail("id",
             "the body has " + std::to_string(b.size()) + " discs (ids 0 .. " + std::to_string(b.size() - 1) + ")");
    return probe;
  }
  if (t == "ke_near") {
    p.validate(kDemKeNearProbeKeys);
    auto probe = std::make_unique<DemProbe>(*this, name, t, "");
    probe->at = p.vec2("at");
    probe->count = p.integer("count", 1);
    return probe;
  }
  p.validate(kDemHeightProbeKeys);
  auto probe = std::make_unique<DemProbe>(*this, name, t, "");
  probe->x = p.number("x");
  probe->band = p.non_negative("band");
  if (probe->band == 0) probe->band = 2 * b.r_max;
  return probe;
}

}  // namespace lagfsi::dem
