// Explicit saturated two-phase MPM, the v-w formulation of Ludeña (2016, sec. 3.5-3.6; digest 2.8),
// one sub-step (mpm_scheme.hpp). Ludeña's eqs. 3.52-3.84 with the digest's sign fixes: p is tension positive,
// sigma = sigma' + p I.
//   water:  m_w a_w = F_w,grav - F_w,int - Q (w - v),   F_w,int = sum V_p p_p grad N,  q = sum n m_w g / k N
//   solid:  m_s a_s = -mbar_w a_w + F_grav + F_trac - F_int,   F_int = sum V_p sigma_p grad N (total stress)
//   then particle velocities (FLIP), MUSL re-map of both velocities, positions with the solid's, and
//   p += dt (K_w / n) [(1 - n) div v + n div w], n from the volume change (incompressible grains).
// Linear elastic skeleton; particle loads act on the mixture.
#include "mpm_scheme.hpp"

#include <lagfsi/time_integrator.hpp>

#include <cmath>

namespace lagfsi::mpm {

namespace {

/// The grid arrays of the two phases (m_s = rho_s V0 and m_w = rho_w V0 the particle's grain and water mass
/// scales, n its porosity).
struct TwoPhaseGrid {
  std::vector<double> solid_mass;       // sum N (1 - n) m_s
  std::vector<double> water_mass;       // sum N m_w (the water's momentum balance)
  std::vector<double> pore_water_mass;  // sum N n m_w (mbar_w, the water in the pores)
  std::vector<double> drag;             // Q = sum N n m_w g / k
  std::vector<Vec2> solid_momentum;     // sum N (1 - n) m_s v
  std::vector<Vec2> water_momentum;     // sum N n m_w w
  std::vector<Vec2> solid_force;        // the mixture's: gravity, loads, internal force of the total stress
  std::vector<Vec2> water_force;        // the water's: gravity, internal force of the pore pressure
  std::vector<Vec2> solid_velocity, water_velocity;
  std::vector<Vec2> solid_acceleration, water_acceleration;
};

class TwoPhase final : public ExplicitScheme {
 public:
  /// c = sqrt((lambda + 2 mu + K_w / n) / rho_sat), with the porosity of the first particle.
  double wave_speed(const MpmBody& b) const override {
    const MpmMaterial& m = *b.material;
    const double n0 = b.particles.porosity[0];
    const double rho_sat = (1 - n0) * m.density() + n0 * b.water.density;
    return std::sqrt((m.lame_lambda() + 2 * m.shear_modulus() + b.water.bulk_modulus / n0) / rho_sat);
  }

 protected:
  void substep(MpmBody& b, double dt) override;

 private:
  TwoPhaseGrid grid_;
};

void TwoPhase::substep(MpmBody& b, double dt) {
  Particles& P = b.particles;
  const MpmMaterial& mat = *b.material;
  const GridBoundaries& bc = b.boundaries;
  const double rho = mat.density(), rho_w = b.water.density, K_w = b.water.bulk_modulus;
  const Index np = static_cast<Index>(P.size());
  const size_t nn = b.grid.mass.size();
  b.locate_particles();
  auto zero = [nn](std::vector<Vec2>& a) { a.assign(nn, Vec2::Zero()); };
  TwoPhaseGrid& G = grid_;
  G.solid_mass.assign(nn, 0.0);
  G.water_mass.assign(nn, 0.0);
  G.pore_water_mass.assign(nn, 0.0);
  G.drag.assign(nn, 0.0);
  zero(G.solid_momentum), zero(G.water_momentum), zero(G.solid_force), zero(G.water_force);
  const Vec2 g = b.gravity();
  // The drag converts the hydraulic conductivity k (m/s) with the unit weight of water rho_w |g|; without
  // gravity (a weightless layer) |g| = 9.81 m/s^2 is used.
  const double g_drag = b.case_gravity.norm() > 0 ? b.case_gravity.norm() : 9.81;
  const double k_hyd = b.water.conductivity;
  for (Index q = 0; q < np; ++q) {
    const Support& sp = b.support[q];
    const double n = P.porosity[q], V = P.volume[q], V0 = P.volume0[q];
    const double ms = rho * V0, mw = rho_w * V0;  // the particle's grain and water mass scales
    const auto& sg = P.stress[q];
    const double pw = P.pore_pressure[q];
    for (int k = 0; k < sp.n; ++k) {
      const Index I = sp.node[k];
      const double N = sp.N[k];
      const Vec2& d = sp.dN[k];
      G.solid_mass[I] += N * (1 - n) * ms;
      G.water_mass[I] += N * mw;
      G.pore_water_mass[I] += N * n * mw;
      G.drag[I] += N * n * mw * g_drag / k_hyd;
      G.solid_momentum[I] += N * (1 - n) * ms * P.v[q];
      G.water_momentum[I] += N * n * mw * P.water_velocity[q];
      const double sxx = sg[0] + pw, syy = sg[1] + pw;  // total stress
      G.solid_force[I] +=
          N * ((1 - n) * ms + n * mw) * g - V * Vec2(sxx * d.x() + sg[2] * d.y(), sg[2] * d.x() + syy * d.y());
      G.water_force[I] += N * mw * g - V * pw * d;
    }
  }
  // Particle loads act on the mixture.
  add_particle_loads(b.loads, b.support, b.t, G.solid_force);
  G.solid_velocity.assign(nn, Vec2::Zero());
  G.water_velocity.assign(nn, Vec2::Zero());
  G.solid_acceleration.assign(nn, Vec2::Zero());
  G.water_acceleration.assign(nn, Vec2::Zero());
  for (size_t I = 0; I < nn; ++I) {
    if (!(G.solid_mass[I] > 0)) continue;
    G.solid_velocity[I] = G.solid_momentum[I] / G.solid_mass[I];
    G.water_velocity[I] = G.water_momentum[I] / G.pore_water_mass[I];
  }
  bc.apply_fixed(G.solid_velocity);
  bc.apply_fixed(G.water_velocity);
  for (size_t I = 0; I < nn; ++I) {
    if (!(G.solid_mass[I] > 0)) continue;
    // The drag is stiff for low conductivity: treated implicitly in w (semi-implicit: the w of the drag at the
    // end of the step), m_w a_w = F - Q (w + dt a_w - v).
    const Vec2 F = G.water_force[I] - G.drag[I] * (G.water_velocity[I] - G.solid_velocity[I]);
    G.water_acceleration[I] = F / (G.water_mass[I] + dt * G.drag[I]);
    G.solid_acceleration[I] = (G.solid_force[I] - G.pore_water_mass[I] * G.water_acceleration[I]) / G.solid_mass[I];
  }
  bc.apply_fixed(G.solid_acceleration);
  bc.apply_fixed(G.water_acceleration);
  for (Index q = 0; q < np; ++q) {
    const Support& sp = b.support[q];
    Vec2 as = Vec2::Zero(), aw = Vec2::Zero();
    for (int k = 0; k < sp.n; ++k) {
      as += sp.N[k] * G.solid_acceleration[sp.node[k]];
      aw += sp.N[k] * G.water_acceleration[sp.node[k]];
    }
    SymplecticEuler::kick(P.v[q], as, dt);  // the particles' velocities, then (below) their positions
    SymplecticEuler::kick(P.water_velocity[q], aw, dt);
  }
  // MUSL re-map of both velocities from the updated particles.
  zero(G.solid_momentum), zero(G.water_momentum);
  for (Index q = 0; q < np; ++q) {
    const Support& sp = b.support[q];
    const double n = P.porosity[q], ms = rho * P.volume0[q], mw = rho_w * P.volume0[q];
    for (int k = 0; k < sp.n; ++k) {
      G.solid_momentum[sp.node[k]] += sp.N[k] * (1 - n) * ms * P.v[q];
      G.water_momentum[sp.node[k]] += sp.N[k] * n * mw * P.water_velocity[q];
    }
  }
  for (size_t I = 0; I < nn; ++I) {
    G.solid_velocity[I] = G.solid_mass[I] > 0 ? Vec2(G.solid_momentum[I] / G.solid_mass[I]) : Vec2::Zero();
    G.water_velocity[I] = G.pore_water_mass[I] > 0 ? Vec2(G.water_momentum[I] / G.pore_water_mass[I]) : Vec2::Zero();
  }
  bc.apply_fixed(G.solid_velocity);
  bc.apply_fixed(G.water_velocity);
  double gw = 0;
  for (Index q = 0; q < np; ++q) {
    const Support& sp = b.support[q];
    Vec2 v = Vec2::Zero();
    Mat2 Ls = Mat2::Zero();
    double divw = 0;
    for (int k = 0; k < sp.n; ++k) {
      v += sp.N[k] * G.solid_velocity[sp.node[k]];
      Ls += G.solid_velocity[sp.node[k]] * sp.dN[k].transpose();
      divw += G.water_velocity[sp.node[k]].dot(sp.dN[k]);
    }
    SymplecticEuler::drift(P.x[q], v, dt);
    gw += P.mass[q] * g.dot(dt * v);
    // Effective stress (linear elastic), pore pressure, porosity, volume.
    const double n = P.porosity[q];
    P.pore_pressure[q] += dt * (K_w / n) * ((1 - n) * (Ls(0, 0) + Ls(1, 1)) + n * divw);
    const double V_old = P.volume[q];
    elastic_increment(P, q, dt * Ls, mat);
    P.porosity[q] = 1 - (1 - n) * V_old / P.volume[q];
    if (!(P.volume[q] > 0) || !std::isfinite(P.pore_pressure[q]) || !(P.porosity[q] > 0 && P.porosity[q] < 1))
      throw b.particle_error(q, "inverted or non-finite");
  }
  b.gravity_work += gw;
}

}  // namespace

std::unique_ptr<ExplicitScheme> make_two_phase_scheme() { return std::make_unique<TwoPhase>(); }

}  // namespace lagfsi::mpm
