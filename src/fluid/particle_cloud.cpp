// The fluid's particle arrays (particle_cloud.hpp): building, compaction, insertion and reordering, the
// only places where the per-particle arrays change size.
#include <lagfsi/fluid/particle_cloud.hpp>

namespace lagfsi::fluid {

void ParticleCloud::assign(const std::vector<Vec2>& x, std::vector<ParticleKind> kind, double h) {
  const Index np = static_cast<Index>(x.size());
  kind_ = std::move(kind);
  state_.x.resize(2 * np);
  for (Index i = 0; i < np; ++i) state_.x.segment<2>(2 * i) = x[i];
  X0_ = state_.x;
  state_.v = Vec::Zero(2 * np);
  state_.a = Vec::Zero(2 * np);
  hvec_.assign(np, h);
  p_ = Vec::Zero(np);
  owed_ = Vec::Zero(np);
}

std::vector<Vec2> ParticleCloud::positions() const {
  const Index np = n();
  std::vector<Vec2> pts(np);
  for (Index i = 0; i < np; ++i) pts[i] = state_.x.segment<2>(2 * i);
  return pts;
}

ParticleCloud::Particle ParticleCloud::particle(Index i) const {
  Particle q;
  q.kind = kind_[i];
  q.h = hvec_[i];
  q.x = state_.x.segment<2>(2 * i);
  q.v = state_.v.segment<2>(2 * i);
  q.a = state_.a.segment<2>(2 * i);
  q.X0 = X0_.segment<2>(2 * i);
  q.p = p_[i];
  q.owed = owed_[i];
  return q;
}

bool ParticleCloud::compact(const std::vector<char>& drop) {
  const Index np = n();
  Index kept = 0;
  for (Index i = 0; i < np; ++i) {
    if (drop[i]) continue;
    kind_[kept] = kind_[i];
    hvec_[kept] = hvec_[i];
    state_.x.segment<2>(2 * kept) = state_.x.segment<2>(2 * i);
    state_.v.segment<2>(2 * kept) = state_.v.segment<2>(2 * i);
    state_.a.segment<2>(2 * kept) = state_.a.segment<2>(2 * i);
    X0_.segment<2>(2 * kept) = X0_.segment<2>(2 * i);
    p_[kept] = p_[i];
    owed_[kept] = owed_[i];
    ++kept;
  }
  if (kept == np) return false;
  kind_.resize(kept);
  hvec_.resize(kept);
  state_.x.conservativeResize(2 * kept);
  state_.v.conservativeResize(2 * kept);
  state_.a.conservativeResize(2 * kept);
  X0_.conservativeResize(2 * kept);
  p_.conservativeResize(kept);
  owed_.conservativeResize(kept);
  return true;
}

void ParticleCloud::append(const std::vector<Particle>& added) {
  const Index np = n();
  const Index nn = np + static_cast<Index>(added.size());
  state_.x.conservativeResize(2 * nn);
  state_.v.conservativeResize(2 * nn);
  state_.a.conservativeResize(2 * nn);
  X0_.conservativeResize(2 * nn);
  p_.conservativeResize(nn);
  owed_.conservativeResize(nn);
  Index k = np;
  for (const Particle& q : added) {
    state_.x.segment<2>(2 * k) = q.x;
    X0_.segment<2>(2 * k) = q.X0;
    state_.v.segment<2>(2 * k) = q.v;
    state_.a.segment<2>(2 * k) = q.a;
    p_[k] = q.p;
    owed_[k] = q.owed;
    kind_.push_back(q.kind);
    hvec_.push_back(q.h);
    ++k;
  }
}

void ParticleCloud::rebuild(const std::vector<Index>& order, const std::vector<Particle>& extra) {
  const Index nn = static_cast<Index>(order.size());
  std::vector<ParticleKind> kind(nn);
  std::vector<double> hv(nn);
  Vec x(2 * nn), v(2 * nn), a(2 * nn), X0(2 * nn), p(nn), owed(nn);
  for (Index k = 0; k < nn; ++k) {
    const Particle q = order[k] >= 0 ? particle(order[k]) : extra[static_cast<size_t>(-1 - order[k])];
    kind[k] = q.kind;
    hv[k] = q.h;
    x.segment<2>(2 * k) = q.x;
    v.segment<2>(2 * k) = q.v;
    a.segment<2>(2 * k) = q.a;
    X0.segment<2>(2 * k) = q.X0;
    p[k] = q.p;
    owed[k] = q.owed;
  }
  kind_ = std::move(kind);
  hvec_ = std::move(hv);
  state_.x = std::move(x);
  state_.v = std::move(v);
  state_.a = std::move(a);
  X0_ = std::move(X0);
  p_ = std::move(p);
  owed_ = std::move(owed);
}

}  // namespace lagfsi::fluid
