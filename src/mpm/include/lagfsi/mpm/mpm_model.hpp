#pragma once
/// @file mpm/mpm_model.hpp
/// The Material Point Method body ("type": "mpm"): particles on a regular background grid, after Sulsky,
/// Chen & Schreyer (1994) and the "modified Lagrangian" (MUSL) algorithm of Ludeña (2016, ch. 3;
/// Al-Kafaji 2013). Plane strain, unit thickness.
///
/// The module (public headers in src/mpm/include/lagfsi/mpm, the rest in src/mpm), one concern per file:
///  - state: particles, grid, shape functions (linear or uGIMP)       mpm_state.hpp, mpm_state.cpp
///  - particle-grid transfers                                         mpm_transfer.hpp, mpm_transfer.cpp
///  - materials: the interface, linear elastic, Mohr-Coulomb          mpm_material.hpp, mpm_material.cpp,
///                                                                    mpm_mohr_coulomb.cpp
///  - what the schemes work on (material, grid, particles, conditions, damping, clock)   mpm_body.hpp
///  - the schemes, chosen once per body (mpm_scheme.hpp): explicit single phase, USL / USF / MUSL
///    (mpm_scheme_explicit.cpp); saturated two-phase, v-w (mpm_two_phase.cpp); implicit Newmark or
///    generalized-alpha on the grid (mpm_implicit.cpp); the explicit sub-stepping (mpm_scheme.cpp)
///  - grid conditions: fixed, prescribed motion, Lysmer-Kuhlemeyer absorbing and free-field
///    boundaries; particle loads                                      mpm_boundaries.hpp, mpm_boundaries.cpp
///  - reading the body from the case                                  mpm_input.cpp
///  - ParaView and CSV output                                         mpm_output.hpp, mpm_output.cpp
///  - probes                                                          mpm_probes.cpp
///  - the PhysicsModel lifecycle                                      mpm_model.cpp
#include <lagfsi/case.hpp>
#include <lagfsi/explicit_model.hpp>
#include <lagfsi/model.hpp>
#include <lagfsi/mpm/mpm_state.hpp>

#include <memory>
#include <string>

namespace lagfsi {

namespace mpm {

struct MpmBody;
class MpmScheme;
class MpmWriter;
struct MpmStepSnapshot;

class MpmModel final : public ExplicitModel {
 public:
  /// Reads the body (its case-file object) and builds its particles, grid, conditions and scheme; throws
  /// InputError for a bad body.
  MpmModel(Params body, const CaseContext& ctx);
  ~MpmModel() override;

  std::string name() const override;
  std::string type() const override { return "mpm"; }
  Index num_nodes() const override;  ///< the particles
  Index num_particles() const override { return num_nodes(); }
  Index num_elements() const override;  ///< the grid's cells
  void initialize() override;
  void write_output(double t) override;
  std::unique_ptr<Probe> make_probe(Params p) override;
  bool can_checkpoint() const override { return true; }
  void serialize(StateArchive& ar) override;  // mpm_checkpoint.cpp

  const Particles& particles() const;
  const Grid& grid() const;
  bool two_phase() const;
  double kinetic_energy() const;
  /// Elastic strain energy sum_p V_p sigma : eps / 2 (linear elastic, small strain).
  double strain_energy() const;
  /// Work of gravity since the start.
  double gravity_work() const;

 protected:
  /// The state at the step's start (MpmStepSnapshot), put back by a retry (ExplicitModel).
  void save_step_start() override;
  void restore_step_start() override;
  /// The whole step (explicit: in sub-steps; implicit: one linear solve); returns the sub-steps.
  int advance(double t_new, double dt) override;

 private:
  CaseContext ctx_;
  std::unique_ptr<MpmBody> body_;
  std::unique_ptr<MpmScheme> scheme_;
  std::unique_ptr<MpmWriter> writer_;
  std::unique_ptr<MpmStepSnapshot> snapshot_;  // the state at the step's start (retry)
  long substeps_ = 0;
};

}  // namespace mpm

/// The MPM body's builder (registered as "mpm" in model_registry() of the app layer, model_registry.hpp).
std::unique_ptr<PhysicsModel> make_mpm_model(Params body, const CaseContext& ctx);

}  // namespace lagfsi
