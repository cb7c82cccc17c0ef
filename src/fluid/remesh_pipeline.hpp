#pragma once
/// @file remesh_pipeline.hpp (private to src/fluid)
/// The PFEM remeshing of a step (remesh_step): the fluid that left the domain box goes, then
///  - "domain_detection": "alpha" (the fractional step's default): the particles are remeshed (Delaunay +
///    alpha shape, meshing/remesh.hpp, then the meniscus, flat and crossing filters), particles too close
///    together are removed and particles are inserted in oversized elements (each followed by a remesh);
///  - "advected" (the monolithic scheme's default) / "level_set" (conservative remeshing,
///    particle_management.cpp): the last step's mesh at the particles' present positions is the predicate of
///    the new domain (meshing/previous_domain.hpp); the particles are managed on it (merged, split, inserted)
///    before one Delaunay triangulation;
/// what the remesh changed (area, kinetic energy) is measured, and the "surface" volume correction moves the
/// free surface.
#include <lagfsi/fluid/particle_cloud.hpp>
#include "fluid_common.hpp"
#include "fluid_energy.hpp"
#include "fluid_mesh.hpp"
#include "ghosts.hpp"
#include "size_field.hpp"
#include "volume_correction.hpp"

#include <lagfsi/meshing/partition.hpp>
#include <lagfsi/meshing/previous_domain.hpp>
#include <lagfsi/meshing/remesh.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace lagfsi::fluid {

/// What the remeshings divided among MPI processes cost (remesh_over_processes), since this process started (a
/// restart counts from it): the ghost layer's size against the particles, the indices every process receives, and
/// this process's time triangulating its part and gathering the others'.
struct DividedRemeshStats {
  long remeshes = 0;
  double ghosts = 0;            ///< summed over the remeshes and the processes
  double particles = 0;         ///< summed over the remeshes (each particle once)
  double gathered_indices = 0;  ///< summed over the remeshes: the indices this process receives from the others
  double part_seconds = 0;      ///< this process: partition, triangulation and classification of its part
  double gather_seconds = 0;    ///< this process: gathering the shares (waiting for the slowest part included)
  /// summary.json's "divided_remeshing" of a fluid body (empty without divided remeshings).
  Json summary(int processes) const;
};

/// meshing::remesh() in a run over MPI processes (mpi_run.hpp): each process remeshes its part of a space partition of
/// the particles with a ghost layer (meshing::remesh_part) and the shares are gathered in rank order, so that every
/// process holds the same mesh: the serial one's elements in another order (the removed and separated faces' counts
/// can differ by faces too large for a part to see whole). With one process, and with the level-set detection (which
/// keeps elements of any size), remesh() itself. A failure on any process throws on every process with its message
/// (divided_remesh.cpp). `stats` (optional) adds the remeshing's cost.
/// `partition` (optional): the processes' parts of pts, as remesh_over_processes would make them (it makes them
/// without).
meshing::RemeshResult remesh_over_processes(const std::vector<Vec2>& pts, const std::vector<ParticleKind>& kind,
                                            const std::vector<double>& h, const meshing::RemeshSettings& settings,
                                            DividedRemeshStats* stats = nullptr,
                                            const meshing::SpacePartition* partition = nullptr);

/// The ghost layer of remesh_over_processes for particles of sizes h, the alpha test's alpha and, with the advected
/// detection, its separation_alpha (0 without).
double divided_halo(const std::vector<double>& h, double alpha, double separation_alpha);

/// Every process's (particle, value) pairs, flattened (i, value, i, value, ...), each process's in increasing particle
/// order and no particle on two processes, gathered on every process in increasing particle order
/// (divided_management.cpp; the pairs themselves with one process). Every process must call it.
std::vector<Index> gather_pairs_in_order(const std::vector<Index>& pairs);

class RemeshPipeline {
 public:
  using Settings = FluidRemeshSettings;
  RemeshPipeline(const FluidConstants& c, ParticleCloud& cloud, FluidMesh& mesh, const Ghosts& ghosts)
      : c_(c), cloud_(cloud), mesh_(mesh), ghosts_(ghosts) {}
  void configure(const Settings& s) { s_ = s; }
  /// The particle size field (size_field.hpp): with an adaptive one the fluid particles take its targets at every
  /// remesh, and the management merges interior pairs that are close for them (coarsen).
  void set_size_field(SizeField f) { size_ = std::move(f); }
  const SizeField& size_field() const { return size_; }
  const Settings& settings() const { return s_; }

  /// The domain box: the walls' box (wall_lo, wall_hi; empty without walls) and the particles `pts`,
  /// enlarged by domain_margin times its larger side. Without it (fixed connectivity) nothing is dropped.
  void set_domain(const Vec2& wall_lo, const Vec2& wall_hi, const std::vector<Vec2>& pts);
  /// The domain box holds `points` too (a structure's boundary, add_ghosts).
  void extend_domain(const std::vector<Vec2>& points);
  /// Moving walls: their box now (lo, hi), which the domain box follows with the structures' margin (set before
  /// each remesh_step).
  void follow_walls(const Vec2& lo, const Vec2& hi) {
    walls_lo_ = lo;
    walls_hi_ = hi;
  }

  /// Open boundaries (fluid_boundary.hpp): `taker` names the outflow (its index) a fluid particle at a position has
  /// left through, or -1, `strip` the outflow in whose strip a point lies, or -1, and `left` receives what each
  /// outflow took: particles and area (drop_outside_domain, less what the remesh fills again in its strip);
  /// `regions` are triangles the advected and level-set detections count as fluid (an inflow's strip).
  void set_open_boundaries(std::function<int(const Vec2&)> taker, std::function<int(const Vec2&)> strip,
                           std::function<void(int, long, double)> left, std::vector<std::array<Vec2, 3>> regions) {
    taker_ = std::move(taker);
    strip_ = std::move(strip);
    left_ = std::move(left);
    open_regions_ = std::move(regions);
  }
  /// Whether a point lies on the face of an inflow or outflow (the particles the surface correction leaves alone).
  void set_open_faces(std::function<bool(const Vec2&)> at_open_face) { at_open_face_ = std::move(at_open_face); }
  /// Whether a point lies on a wall that holds its particles by constraints: the surface correction leaves them
  /// alone too (moved along the area's gradient, a particle at the water's edge on a wall leaves the wall's line,
  /// and the wall puts it back in the step: the correction and the step undo each other, and the churn scatters
  /// the water). `on_fixed_wall_line`: the same for the walls that do not move, along which the domain detection's
  /// separation test leaves water against a wall (meshing::RemeshSettings::on_wall; a moving wall's particles are
  /// put back on its new line after each step, and a flat element kept along it inverts as the wall turns).
  void set_wall_lines(std::function<bool(const Vec2&)> on_wall_line,
                      std::function<bool(const Vec2&)> on_fixed_wall_line) {
    on_wall_line_ = std::move(on_wall_line);
    on_fixed_wall_line_ = std::move(on_fixed_wall_line);
  }

  /// The depth of a point at time t in the solid behind the walls' particles ("wall_model": "particles"; negative
  /// on the fluid side, zero on a wall's line). A fluid particle pressed onto a wall's line between two of its
  /// particles then goes as one pressed against a wall particle (merge_pressed_against_walls), and the advected
  /// and level-set detections count as fluid the triangles of wall particles alone that lie on the
  /// fluid side and touch the fluid's mesh, through an edge or through another such triangle (wet corners): at a
  /// corner where two walls meet at less than 180 degrees on the fluid's side (a cylinder and the plate behind it),
  /// the Delaunay triangles between the corner's wall particles belong to no element, and a fluid particle coming
  /// close to the corner would otherwise make elements outside the advected domain with two wall particles, which
  /// the detection refuses (a dry wall's meniscus): the corner became a free surface, a hole with p = 0 that a wake's
  /// suction opened into a cavity and carried downstream.
  void set_wall_solid(std::function<double(const Vec2&, double)> depth) { wall_depth_ = std::move(depth); }

  /// A triangle of the fluid regions (build_particles): the initial domain of the advected and level-set
  /// detections.
  void add_region_triangle(const std::array<Vec2, 3>& t) { region_triangles_.push_back(t); }
  /// The initial mesh (initialize, PFEM mode): with the advected and level-set detections the regions
  /// themselves are the domain: the Delaunay elements whose centroid lies in them (with the separation
  /// test), none outside (a level set of zero band). The alpha shape would cut the corners where the surface
  /// meets a wall, which the advected domain would then keep filling and emptying. With "alpha", remesh_now.
  void initial_mesh();
  /// The regions' triangles are freed (only the initial domain needs them).
  void free_regions() { std::vector<std::array<Vec2, 3>>().swap(region_triangles_); }

  /// The whole remeshing of a step (predict, t_new the end of the step): drop_outside_domain; with "alpha"
  /// remesh_now, remove_close_particles, insert_particles (each change remeshed again), otherwise particle
  /// management on the advected domain and one remesh; the change of area and energies it made (`energy`
  /// measures them); then the "surface" correction. `on_wall` (empty, or per particle the number of its
  /// components constrained by a wall: "wall_model": "constraints") keeps the particles on walls in place
  /// when merged.
  void remesh_step(double t_new, VolumeCorrection& volume, const FluidEnergy& energy,
                   const std::vector<char>& on_wall = {});
  /// Delaunay + domain detection of the present cloud: the alpha shape, or (advected / level set) the
  /// previous domain `previous` as predicate; then the meniscus, flat-element and structure-crossing filters;
  /// the free-surface flags of what is left.
  /// `partition` (optional, an MPI run): the processes' parts of the present cloud (remesh_over_processes).
  void remesh_now(const meshing::PreviousDomain* previous = nullptr,
                  const meshing::SpacePartition* partition = nullptr);
  /// free and connected of the mesh from its elements: particles of edges used by one element, unless both
  /// ends are on a wall (`on_wall`) and, when `along_wall` is given, the edge's midpoint lies on one
  /// (FluidWalls::on_a_segment: not the long side of a corner's triangle); only Fluid particles are free
  /// surface.
  void mark_free_surface(const std::vector<char>& on_wall,
                         const std::function<bool(const Vec2&)>& along_wall = nullptr);
  /// Removes fluid particles closer than close_fraction * h to another particle; true when some were.
  bool remove_close_particles();
  /// Inserts particles at the centroids of the oversized elements; true when some were.
  bool insert_particles();
  /// An adaptive size field under the alpha detection, on the mesh just made: the fluid particles take its targets at
  /// t (sources: the free surface, the particles in an element with a wall's or a structure's particle and those in
  /// no element), and interior pairs closer than 0.6 of their mean size merge (coarsen_pairs); true when some did.
  bool follow_size_field_alpha(double t);
  /// Removes the fluid particles outside the domain box and those an outflow takes (their share of the mesh's area
  /// leaves `volume`'s reference); throws SolverError when none is left (t_new in the message).
  bool drop_outside_domain(double t_new, VolumeCorrection& volume);
  /// The mesh's area in each outflow's strip (indexed by the boundary's index; empty without outflows).
  std::vector<double> outlet_strip_areas() const;

  /// Remeshing's effect in the last step (log.csv remesh_dA, remesh_dKE).
  double area_change() const { return remesh_dA_; }
  double kinetic_energy_change() const { return remesh_dKE_; }
  /// summary.json's "remeshing" block, but for the detection's name and the volume correction's energy.
  Json summary() const;
  /// Checkpoints (state_archive.hpp; fluid_checkpoint.cpp).
  void serialize(StateArchive& ar);

 private:
  /// The margin around a structure's boundary (extend_domain, drop_outside_domain): domain_margin times the
  /// larger side of the box without set_domain's margin.
  double structure_margin() const {
    return s_.domain_margin * (domain_hi_ - domain_lo_).maxCoeff() / (1 + 2 * s_.domain_margin);
  }
  /// The boundary of the mesh as chains: next[i] / prev[i] the particle after / before i along a boundary
  /// edge (directed as in its element), -1 if none; pinched where two boundary edges leave one particle (two
  /// surfaces touching at it).
  struct BoundaryChains {
    std::vector<Index> next, prev;
    std::vector<char> pinched;
  };
  BoundaryChains boundary_chains() const;
  /// The advected domain's elements and boundary edges (meshing::PreviousDomain's).
  struct AdvectedDomain {
    std::vector<std::array<Vec2, 3>> triangles;
    std::vector<std::array<Vec2, 2>> boundary;
  };
  /// The mesh of the last step at the particles' present positions, as the predicate of the next domain
  /// (particle_management.cpp); `chain`: its boundary_chains().
  AdvectedDomain advected_domain(const BoundaryChains& chain) const;
  /// Conservative particle management on the advected mesh (particle_management.cpp): close fluid pairs are
  /// merged (mass-weighted state; on the free surface at the position that keeps the boundary's area), long
  /// free-surface edges are split at their midpoints and large elements get a particle at their centroid
  /// (state interpolated on the mesh). Keeps the mesh consistent with the cloud. Returns true if it changed
  /// it. `meshed` and `boundary_edges` receive the previous mesh's topology in the new numbering (the
  /// particles it used, inserted ones included; its boundary edges, through merges and splits), and, when
  /// `all_edges` is given, every edge of the previous mesh through merges (an edge of a removed particle goes;
  /// a split boundary edge gives its two halves). `chain`: the mesh's boundary_chains().
  bool manage_particles(const BoundaryChains& chain, std::vector<std::uint8_t>& meshed,
                        std::vector<std::pair<Index, Index>>& boundary_edges,
                        std::vector<std::pair<Index, Index>>* all_edges = nullptr,
                        const std::vector<char>& on_wall = {});
  /// manage_particles' stages (particle_management.cpp), in order; Management: what they share.
  struct Management;
  /// A particle to insert: its state interpolated on the advected mesh.
  struct NewParticle {
    Vec2 x, v, a;
    double p, h;
  };
  Management start_management(const BoundaryChains& chain, const std::vector<char>& on_wall) const;
  void merge_onto_walls(Management& m);
  void merge_pressed_against_walls(Management& m);
  void merge_close_pairs(Management& m);
  /// An MPI run: the fluid particles not yet touched that have another within close_fraction h_max, in increasing
  /// index, each process finding those of its part of space (Management::part) and every process all of them
  /// (divided_management.cpp).
  std::vector<Index> meeting_candidates(const Management& m, double cell) const;
  void coarsen(Management& m);
  /// The particles refinement asks for (in the order they are tried): at the midpoints of long boundary edges (`from`:
  /// each one's edge's first particle) and at the centroids of large elements.
  std::vector<NewParticle> split_long_edges(const Management& m, std::vector<Index>& from) const;
  std::vector<NewParticle> insert_in_large_elements(const Management& m) const;
  void carry_topology(Management& m, bool all_edges) const;
  bool apply_management(Management& m, std::vector<std::uint8_t>& meshed,
                        std::vector<std::pair<Index, Index>>& boundary_edges,
                        std::vector<std::pair<Index, Index>>* all_edges);
  /// Merges the pair (i, j) into one particle with the pair's mass-weighted state; leave_to_wall removes the
  /// fluid particle f, which the wall or ghost particle g then stands for.
  void merge_pair(Management& m, Index i, Index j);
  void leave_to_wall(Management& m, Index f, Index g);
  /// An adaptive size field: the fluid particles' sizes become its targets on the advected mesh at t (sources: the
  /// mesh's boundary, the wall and ghost particles and the particles on walls).
  void follow_size_field(const BoundaryChains& chain, const std::vector<char>& on_wall, double t);
  /// The fluid particles' sizes: the size field's targets at t on the mesh from the features `source` (per particle;
  /// the flow indicator's particles are added to it).
  void apply_size_field(std::vector<char>& source, double t);
  /// The pairs of particles joined by an edge of the mesh, both `interior`, closer than 0.6 of their mean size, the
  /// closest (relative to their size) first.
  std::vector<std::pair<Index, Index>> coarsen_pairs(const std::vector<Vec2>& pts,
                                                     const std::function<bool(Index)>& interior) const;
  /// The wet corners (set_wall_solid) of the mesh just made, from the Delaunay triangles of wall particles alone
  /// (`faces`), at time t.
  void find_wet_corners(const std::vector<std::array<Index, 3>>& faces, double t);
  /// Removes the flagged particles (fluid only) from the cloud; the elements of the mesh that use a removed
  /// particle go, the others are renumbered (renumber_).
  bool drop_particles(const std::vector<char>& drop);
  /// Appends a fluid particle with the given state (an inserted particle: X0 = x).
  void append_particle(const Vec2& x, const Vec2& v, const Vec2& a, double p, double h);

  const FluidConstants& c_;
  ParticleCloud& cloud_;
  FluidMesh& mesh_;
  const Ghosts& ghosts_;
  Settings s_;
  SizeField size_;
  Vec2 domain_lo_ = Vec2::Constant(1.0), domain_hi_ = Vec2::Constant(-1.0);  // empty: fixed connectivity
  Vec2 walls_lo_ = Vec2::Constant(1.0), walls_hi_ = Vec2::Constant(-1.0);    // moving walls' box (follow_walls)
  std::vector<std::array<Vec2, 3>> region_triangles_;  // the fluid regions' elements (the initial domain)
  std::function<int(const Vec2&)> taker_;              // open boundaries (set_open_boundaries)
  std::function<int(const Vec2&)> strip_;
  std::function<void(int, long, double)> left_;
  std::vector<std::array<Vec2, 3>> open_regions_;
  std::function<bool(const Vec2&)> at_open_face_;          // set_open_faces
  std::function<bool(const Vec2&)> on_wall_line_;          // set_wall_lines
  std::function<bool(const Vec2&)> on_fixed_wall_line_;    // set_wall_lines
  std::function<double(const Vec2&, double)> wall_depth_;  // set_wall_solid
  // Triangles of wall particles (never removed: their indices stay) counted as fluid by the next advected domain
  // (find_wet_corners).
  std::vector<std::array<Index, 3>> wet_corners_;
  double t_remesh_ = 0;          // the time of the remesh under way (remesh_step)
  std::vector<Index> renumber_;  // the last drop_particles: old index -> new index, -1 if dropped
  std::vector<Index> survivor_;  // the last manage_particles: old index -> new index of it, of its merge's
                                 // survivor or of the wall particle that stands for it (-1: none)
  // Remeshing's effect per step (log.csv) and over the run (summary.json).
  double remesh_dA_ = 0, remesh_dKE_ = 0;
  double remesh_area_added_ = 0, remesh_area_removed_ = 0, remesh_ke_total_ = 0, remesh_pe_total_ = 0;
  DividedRemeshStats divided_;  // not checkpointed: this process's since it started
  long merged_ = 0, merged_meeting_ = 0, split_ = 0, inserted_ = 0, added_outside_ = 0, separated_ = 0,
       wall_removed_ = 0, kept_edges_ = 0, coarsened_ = 0;
  double area_excess_ = 0;  // area of the elements added outside the advected domain, less those torn off
};

}  // namespace lagfsi::fluid
