#pragma once
/// @file dem/dem_blast.hpp
/// Air-blast load of a point TNT charge on the exposed discs (Sabatucci et al., CILAMCE 2013, Sec. 4;
/// shared/spec/004_dem.md Sec. 2.5). The charge (W kg TNT at G) is not a body: each exposed disc gets
///   F = Pe(R, t) * L * 1 m   along G -> centre,
/// with R = |centre - G|, Z = R / W^(1/3) (clamped to [0.05, 10]) and
///  - Henrych (1979) peak side-on overpressure Ps(Z) [kPa]: 1407.2/Z + 554/Z^2 - 35.7/Z^3 + 0.625/Z^4
///    (0.05 <= Z < 0.3), 619.4/Z - 326/Z^2 + 213.2/Z^3 (0.3 <= Z < 1), 66.2/Z + 405/Z^2 + 328.8/Z^3 (1 <= Z <= 10);
///  - positive phase td = 0.5 R^0.72 W^0.16 ms (Wu & Hao 2005);
///  - arrival ta = R / Us (default, "direct") or the integral of dr / Us(r) ("integrated"), Us = a0 sqrt(1 + 6 Ps /
///    (7 p0)) (Rankine-Hugoniot; the paper's Eq. 4 is its Mach number), a0 = 340 m/s, p0 = 101.325 kPa;
///  - Friedlander Pe = Ps (1 - s) exp(-beta s), s = (t - ta)/td, for 0 <= s <= 1 (no negative phase), beta = 1;
///  - shadowing: the discs sorted by distance from G; each disc blocks the angular interval [phi - alpha,
///    phi + alpha], alpha = asin(r/d), of the directions seen from G; the still-free part [psi1, psi2] of its
///    interval (offsets from its centre direction) is loaded over the arc L = r |theta(psi2) - theta(psi1)|,
///    theta(psi) = asin((d/r) sin psi) - psi ("area": "arc", the paper's reading), or over the projected width
///    r |sin theta(psi2) - sin theta(psi1)| ("area": "projected").
/// The load acts for t <= t_end (2.5 ms in the paper). The exposure (which arcs are free) depends on the
/// positions only; it is recomputed every `exposure_every` steps (1 = every step, as the paper).
/// Cost: the sweep keeps the distance order of the last update and repairs it by insertion sort (the discs move
/// little between updates; a full sort after the discs were reordered), represents directions by a monotone
/// pseudo-angle (no trigonometry for the discs in the shadow: the tangent directions from a square root), skips
/// the blocked set's update for a disc wholly in the shadow, and computes the angles only for the loaded arcs.
#include <lagfsi/params.hpp>
#include <lagfsi/state_archive.hpp>

#include <map>
#include <vector>

namespace lagfsi::dem {

/// Henrych peak side-on overpressure [kPa] at scaled distance Z [m/kg^(1/3)] (Z clamped to [0.05, 10]).
double henrych_overpressure_kpa(double z);
/// Wu & Hao positive-phase duration [s] at distance R [m] of W [kg TNT].
double wu_hao_duration(double r, double w);
/// Shock-front speed [m/s] for the peak overpressure ps [Pa].
double shock_speed(double ps, double p0 = 101325.0, double a0 = 340.0);

class Blast {
 public:
  /// Reads the body's "blast" object.
  explicit Blast(Params p);
  /// Arrival time at distance R.
  double arrival(double r) const;
  /// The overpressure [Pa] at distance R and time t (0 outside the positive phase).
  double pressure(double r, double t) const;
  /// Adds the blast forces at time t to f (2 per disc) for discs at x (stride) with radii r; step counts
  /// the calls (the exposure is recomputed every exposure_every calls). Returns the number of loaded discs.
  int apply(const double* x, int stride, const double* r, int n, double t, std::vector<double>& f);
  bool active(double t) const { return t <= t_end_; }
  Vec2 charge() const { return g_; }
  double mass() const { return w_; }
  /// The loaded length of each disc at the last exposure update (for output).
  const std::vector<double>& exposed() const { return exposed_; }
  /// The disc order changed: recompute the exposure (and sort the discs afresh) at the next call.
  void invalidate() {
    calls_ = 0;
    order_valid_ = false;
  }
  /// Checkpoints: the exposure of the last update, the calls since it and the distance order (dem_checkpoint.cpp).
  void serialize(StateArchive& ar);

 private:
  void update_exposure(const double* x, int stride, const double* r, int n);
  Vec2 g_;
  double w_, w13_, t_end_, beta_, p0_, a0_;
  bool integrated_, projected_;
  int every_, calls_ = 0;
  std::vector<double> exposed_;  // loaded length per disc
  std::vector<int> order_;       // discs by distance from G at the last update
  bool order_valid_ = false;
  std::vector<double> dist_, lo_, hi_;  // scratch: distance, tangent directions (pseudo-angles)
  std::map<double, double> occupied_;   // scratch: blocked directions
};

}  // namespace lagfsi::dem
