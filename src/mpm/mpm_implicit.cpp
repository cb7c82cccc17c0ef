// Implicit MPM (mpm_scheme.hpp): one step of the analysis' Newmark or generalized-alpha (the solid's integrator
// objects) on the grid; linear elastic, small strain, single phase, undamped, one linear solve per step (the
// problem is linear within the step).
//
// Grid state at t_n from the particles: positions of the nodes, velocities and accelerations mapped with the
// particles' masses. The step's unknowns are the new node positions x_{n+1} (2 per node, as for the solid);
// the time integrator gives a(x) and v(x), and the residual
//   r(x) = M a(x) + f_int(x) - f_ext,   f_int = sum_p V_p B_p^T (sigma_p + D : sym(grad (x - x_n))),
// is linear in x (small strain), so one solve with H = c_m M + c_k K is exact. Empty nodes are held.
#include "mpm_scheme.hpp"

#include <lagfsi/system_assembly.hpp>

namespace lagfsi::mpm {

namespace {

class Implicit final : public MpmScheme {
 public:
  Implicit(std::unique_ptr<TimeIntegrator> integrator, std::unique_ptr<LinearSolver> solver)
      : integrator_(std::move(integrator)), solver_(std::move(solver)) {}
  int advance(MpmBody& b, double t_new, double dt) override {
    step(b, t_new, dt);
    b.t = t_new;
    return 1;
  }

 private:
  void step(MpmBody& b, double t_new, double dt);

  std::unique_ptr<TimeIntegrator> integrator_;
  std::unique_ptr<LinearSolver> solver_;
};

void Implicit::step(MpmBody& b, double t_new, double dt) {
  Particles& P = b.particles;
  const Grid& grid = b.grid;
  const MpmMaterial& mat = *b.material;
  const double lambda = mat.lame_lambda(), mu = mat.shear_modulus();
  const Index np = static_cast<Index>(P.size());
  const Index nn = static_cast<Index>(grid.mass.size());
  b.locate_particles();
  Vec mass = Vec::Zero(nn), mv = Vec::Zero(2 * nn), ma = Vec::Zero(2 * nn), fext = Vec::Zero(2 * nn),
      fint0 = Vec::Zero(2 * nn);
  const Vec2 g = b.gravity();
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(np) * 18 * 18);
  for (Index q = 0; q < np; ++q) {
    const Support& sp = b.support[q];
    const auto& sg = P.stress[q];
    const double V = P.volume[q], mq = P.mass[q];
    for (int k = 0; k < sp.n; ++k) {
      const Index I = sp.node[k];
      const double N = sp.N[k];
      const Vec2& d = sp.dN[k];
      mass[I] += N * mq;
      mv.segment<2>(2 * I) += N * mq * P.v[q];
      ma.segment<2>(2 * I) += N * mq * P.acceleration[q];
      fext.segment<2>(2 * I) += N * mq * g;
      fint0.segment<2>(2 * I) += V * Vec2(sg[0] * d.x() + sg[2] * d.y(), sg[2] * d.x() + sg[1] * d.y());
      // K_IJ = V B_I^T D B_J (plane strain, small strain)
      for (int l = 0; l < sp.n; ++l) {
        const Vec2& e = sp.dN[l];
        const Index J = sp.node[l];
        const double kxx = V * ((lambda + 2 * mu) * d.x() * e.x() + mu * d.y() * e.y());
        const double kxy = V * (lambda * d.x() * e.y() + mu * d.y() * e.x());
        const double kyx = V * (lambda * d.y() * e.x() + mu * d.x() * e.y());
        const double kyy = V * ((lambda + 2 * mu) * d.y() * e.y() + mu * d.x() * e.x());
        trip.emplace_back(2 * I, 2 * J, kxx);
        trip.emplace_back(2 * I, 2 * J + 1, kxy);
        trip.emplace_back(2 * I + 1, 2 * J, kyx);
        trip.emplace_back(2 * I + 1, 2 * J + 1, kyy);
      }
    }
  }
  {  // the loads at the end of the step
    std::vector<Vec2> fl(nn, Vec2::Zero());
    add_particle_loads(b.loads, b.support, t_new, fl);
    for (Index I = 0; I < nn; ++I) fext.segment<2>(2 * I) += fl[I];
  }
  // Held dofs: empty nodes and fixed components; prescribed motion is not available implicitly.
  std::vector<char> held(2 * nn, 0);
  for (Index I = 0; I < nn; ++I)
    if (!(mass[I] > 0)) held[2 * I] = held[2 * I + 1] = 1;
  for (const auto& [node, comp] : b.boundaries.fixed) held[2 * node + comp] = 1;
  KinematicState s;
  s.t = b.t;
  s.x = Vec::Zero(2 * nn);
  s.v = Vec::Zero(2 * nn);
  s.a = Vec::Zero(2 * nn);
  for (Index I = 0; I < nn; ++I) {
    s.x.segment<2>(2 * I) = grid.node_position(I % (grid.nx + 1), I / (grid.nx + 1));
    if (mass[I] > 0) {
      s.v.segment<2>(2 * I) = mv.segment<2>(2 * I) / mass[I];
      s.a.segment<2>(2 * I) = ma.segment<2>(2 * I) / mass[I];
    }
  }
  for (Index d = 0; d < 2 * nn; ++d)
    if (held[d]) s.v[d] = s.a[d] = 0.0;
  integrator_->begin_step(s, dt);
  const TangentCoefficients cf = integrator_->coefficients();
  SparseMatrix K(2 * nn, 2 * nn);
  K.setFromTriplets(trip.begin(), trip.end());
  // Linear: r(x) = M a(x) + fint0 + K (x_eval - x_n) - fext; one Newton step from the predictor.
  Vec x = integrator_->predictor();
  const EvalPoint ev = integrator_->kinematics(x);
  Vec r = Vec::Zero(2 * nn);
  for (Index I = 0; I < nn; ++I) r.segment<2>(2 * I) = mass[I] * ev.a.segment<2>(2 * I);
  r += fint0 + K * (ev.x - s.x) - fext;
  SparseMatrix& H = K;
  combine_tangent_lumped(H, cf.c_k, cf.c_m, mass);
  dirichlet_identity(H, r, held);
  for (Index d = 0; d < 2 * nn; ++d)
    if (held[d] && H.coeff(d, d) == 0.0) H.coeffRef(d, d) = 1.0;
  H.makeCompressed();
  solver_->setup(H);
  Vec dx;
  solver_->solve(-r, dx);
  x += dx;
  KinematicState e;
  integrator_->end_step(x, e);
  // Grid to particles: FLIP velocity and acceleration, positions and stresses from the grid displacement.
  const Vec du = x - s.x;
#pragma omp parallel for schedule(static) if (np >= 20000)
  for (Index q = 0; q < np; ++q) {
    const Support& sp = b.support[q];
    Vec2 dv = Vec2::Zero(), a = Vec2::Zero(), u = Vec2::Zero();
    Mat2 G = Mat2::Zero();  // grad of the displacement increment
    for (int k = 0; k < sp.n; ++k) {
      const Index I = sp.node[k];
      dv += sp.N[k] * (e.v.segment<2>(2 * I) - s.v.segment<2>(2 * I));
      a += sp.N[k] * e.a.segment<2>(2 * I);
      u += sp.N[k] * du.segment<2>(2 * I);
      G += du.segment<2>(2 * I) * sp.dN[k].transpose();
    }
    P.v[q] += dv;
    P.acceleration[q] = a;
    P.x[q] += u;
    elastic_increment(P, q, G, mat);
  }
}

}  // namespace

std::unique_ptr<MpmScheme> make_implicit_scheme(std::unique_ptr<TimeIntegrator> integrator,
                                                std::unique_ptr<LinearSolver> solver) {
  return std::make_unique<Implicit>(std::move(integrator), std::move(solver));
}

}  // namespace lagfsi::mpm
