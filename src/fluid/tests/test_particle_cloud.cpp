// Unit tests of the PFEM fluid's particle arrays (src/fluid/include/lagfsi/fluid/particle_cloud.hpp): compact, append
// and rebuild keep every per-particle array aligned. Each particle i of a
// test cloud carries values derived from a tag (x = (t, 2t), v = (3t, 4t), a = (5t, 6t), X0 = (7t, 8t),
// p = 9t, h = 10t, owed area 11t), so a misaligned array shows as a value of another particle's tag.
#include <lagfsi/fluid/particle_cloud.hpp>

#include <gtest/gtest.h>

#include <vector>

namespace {

using lagfsi::Index;
using lagfsi::Vec2;
using lagfsi::fluid::ParticleCloud;
using lagfsi::fluid::ParticleKind;

ParticleCloud::Particle tagged(double t, ParticleKind kind = ParticleKind::Fluid) {
  ParticleCloud::Particle q;
  q.kind = kind;
  q.h = 10 * t;
  q.x = Vec2(t, 2 * t);
  q.v = Vec2(3 * t, 4 * t);
  q.a = Vec2(5 * t, 6 * t);
  q.X0 = Vec2(7 * t, 8 * t);
  q.p = 9 * t;
  q.owed = 11 * t;
  return q;
}

/// A cloud of particles tagged 1..n (the first `walls` of them walls).
ParticleCloud make_cloud(int n, int walls) {
  ParticleCloud c;
  std::vector<ParticleCloud::Particle> qs;
  for (int i = 0; i < n; ++i) qs.push_back(tagged(i + 1, i < walls ? ParticleKind::Wall : ParticleKind::Fluid));
  c.append(qs);
  return c;
}

/// Every array of particle i holds tag t's values, and the arrays have the cloud's size.
void expect_particle(const ParticleCloud& c, Index i, double t, ParticleKind kind) {
  ASSERT_EQ(c.x().size(), 2 * c.n());
  ASSERT_EQ(c.v().size(), 2 * c.n());
  ASSERT_EQ(c.a().size(), 2 * c.n());
  ASSERT_EQ(c.X0().size(), 2 * c.n());
  ASSERT_EQ(c.p().size(), c.n());
  ASSERT_EQ(c.owed().size(), c.n());
  ASSERT_EQ(static_cast<Index>(c.h().size()), c.n());
  const ParticleCloud::Particle q = c.particle(i), e = tagged(t, kind);
  EXPECT_EQ(q.kind, e.kind) << "particle " << i;
  EXPECT_EQ(q.h, e.h) << "particle " << i;
  EXPECT_EQ(q.x, e.x) << "particle " << i;
  EXPECT_EQ(q.v, e.v) << "particle " << i;
  EXPECT_EQ(q.a, e.a) << "particle " << i;
  EXPECT_EQ(q.X0, e.X0) << "particle " << i;
  EXPECT_EQ(q.p, e.p) << "particle " << i;
  EXPECT_EQ(q.owed, e.owed) << "particle " << i;
}

TEST(ParticleCloud, AssignStartsAtRestWithX0AtThePositions) {
  ParticleCloud c;
  c.assign({Vec2(1, 2), Vec2(3, 4)}, {ParticleKind::Wall, ParticleKind::Fluid}, 0.5);
  ASSERT_EQ(c.n(), 2);
  EXPECT_EQ(c.kind(0), ParticleKind::Wall);
  EXPECT_TRUE(c.is_fluid(1));
  EXPECT_EQ(c.pos(1), Vec2(3, 4));
  EXPECT_EQ(c.X0(), c.x());
  EXPECT_EQ(c.v().norm() + c.a().norm() + c.p().norm() + c.owed().norm(), 0.0);
  EXPECT_EQ(c.h(0), 0.5);
  EXPECT_EQ(c.positions()[0], Vec2(1, 2));
}

TEST(ParticleCloud, CompactKeepsTheArraysAligned) {
  ParticleCloud c = make_cloud(6, 2);
  EXPECT_FALSE(c.compact(std::vector<char>(6, 0)));  // nothing flagged: unchanged
  ASSERT_EQ(c.n(), 6);
  EXPECT_TRUE(c.compact({0, 0, 1, 0, 1, 0}));
  ASSERT_EQ(c.n(), 4);
  expect_particle(c, 0, 1, ParticleKind::Wall);
  expect_particle(c, 1, 2, ParticleKind::Wall);
  expect_particle(c, 2, 4, ParticleKind::Fluid);
  expect_particle(c, 3, 6, ParticleKind::Fluid);
}

TEST(ParticleCloud, AppendAddsAtTheEnd) {
  ParticleCloud c = make_cloud(3, 1);
  c.append({tagged(10), tagged(11)});
  ASSERT_EQ(c.n(), 5);
  expect_particle(c, 0, 1, ParticleKind::Wall);
  expect_particle(c, 2, 3, ParticleKind::Fluid);
  expect_particle(c, 3, 10, ParticleKind::Fluid);
  expect_particle(c, 4, 11, ParticleKind::Fluid);
}

TEST(ParticleCloud, RebuildReordersAndInsertsExtraParticles) {
  // walls, then two extra (ghost) particles, then the fluid without particle 3: add_ghosts' order.
  ParticleCloud c = make_cloud(5, 2);
  c.rebuild({0, 1, -1, -2, 2, 4}, {tagged(20, ParticleKind::Ghost), tagged(21, ParticleKind::Ghost)});
  ASSERT_EQ(c.n(), 6);
  expect_particle(c, 0, 1, ParticleKind::Wall);
  expect_particle(c, 1, 2, ParticleKind::Wall);
  expect_particle(c, 2, 20, ParticleKind::Ghost);
  expect_particle(c, 3, 21, ParticleKind::Ghost);
  expect_particle(c, 4, 3, ParticleKind::Fluid);
  expect_particle(c, 5, 5, ParticleKind::Fluid);
  EXPECT_EQ(c.n_boundary_particles(), 4);  // walls and ghosts lead the cloud
}

TEST(ParticleCloud, BoundaryParticlesAreTheLeadingNonFluidOnes) {
  EXPECT_EQ(make_cloud(5, 2).n_boundary_particles(), 2);
  EXPECT_EQ(make_cloud(3, 0).n_boundary_particles(), 0);
  EXPECT_EQ(make_cloud(3, 3).n_boundary_particles(), 3);
  EXPECT_EQ(ParticleCloud().n_boundary_particles(), 0);
}

}  // namespace
