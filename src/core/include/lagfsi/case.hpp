#pragma once
/// @file case.hpp
/// The case file: what every model builder receives and the shared geometry and selection helpers. The
/// registry that turns a body's "type" string into a model is the app layer's (model_registry.hpp): the core
/// knows no model.
///
/// A case file (JSON, comments allowed) has the top-level keys documented by case_defaults(); each body
/// and each nested object is validated against its own defaults (see the builders), so `lagfsi check`
/// prints the whole resolved case with every default filled in.
#include <lagfsi/linear_solver.hpp>
#include <lagfsi/mesh.hpp>
#include <lagfsi/model.hpp>
#include <lagfsi/params.hpp>
#include <lagfsi/time_integrator.hpp>

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace lagfsi {

struct NewtonSettings {
  int max_iterations = 25;
  double residual_tolerance = 1e-6;  ///< relative to the largest force term of the step (inertia, internal, external)
  double position_tolerance = 1e-9;  ///< relative to the body size
};

/// How a dynamic analysis chooses its step (/analysis/time_step): fixed (the analysis' dt, halved only to retry a
/// failed step) or adaptive: each step the smallest of the ceiling, `growth` times the last step and every model's
/// stable step for the Courant number `courant` (PhysicsModel::stable_step).
struct TimeStepControl {
  bool adaptive = false;
  double courant = 0.5;
  double max = 0;  ///< the ceiling (s)
  double growth = 1.25;
};

struct AnalysisSettings {
  std::string type;           ///< "static" (load factor = time from 0 to 1) or "dynamic"
  double dt = 0;              ///< time step (dynamic) or 1/load_steps (static)
  double end_time = 0;        ///< 1 for static
  IntegratorSpec integrator;  ///< the implicit models' integrator (/analysis/integrator, read once)
  NewtonSettings newton;
  LinearSolverSettings linear_solver;  ///< the solids' Newton systems (linear_solver.hpp)
  int max_step_halvings = 4;           ///< retries of a failed step with dt/2, dt/4, ...
  TimeStepControl time_step;           ///< fixed or adaptive (dynamic analyses)
};

/// What a model builder gets besides its own parameters.
struct CaseContext {
  std::filesystem::path case_file;
  std::filesystem::path base_dir;  ///< folder of the case file (relative paths start here)
  std::filesystem::path out_dir;
  AnalysisSettings analysis;
  Vec2 gravity = Vec2::Zero();
  bool quiet = false;  ///< --quiet: no progress and no warnings on stderr (errors only; notes go to summary.json)
};

/// Top-level defaults of a case file (null = required).
const Json& case_defaults();

/// Mesh of a geometry primitive. geometry: {"type": "rectangle", "origin": [x, y], "size": [w, h]} |
/// {"type": "polygon", "points": [[x, y], ...], "holes": [[[x, y], ...], ...]} |
/// {"type": "circle_cut", "points": [...], "centre": [x, y], "radius": r} (a polygon minus a disc that
/// cuts its boundary in exactly two points, e.g. a flag clamped on a cylinder).
/// mesh: {"size": h, "order": 1|2|3, "type": "unstructured"|"structured", "divisions": [nx, ny],
/// "pattern": "crossed"|"right"|"left"} ("structured" for rectangles only).
/// `size` (unstructured meshes): a local target size at a point, at least the mesh's "size" (meshing::mesh_polygon).
TriMesh build_mesh(Params geometry, Params mesh, const std::function<double(const Vec2&)>& size = nullptr);

/// The most nodes build_mesh makes for one mesh (after elevation to its order), 2 million unless set: a mesh past it
/// is refused as a likely mistake (a size in the wrong unit meshes for minutes and fills the memory). Runs that
/// need more raise it (`lagfsi run --max-nodes N`); the process-wide value is set before the case is built.
double max_mesh_nodes();
void set_max_mesh_nodes(double nodes);

/// The outline of a "circle_cut" geometry (counter-clockwise like its polygon), the arc in pieces of about h.
std::vector<Vec2> circle_cut_outline(Params geometry, double h);
/// The loops that bound a geometry (its outer loop, then its holes; a circle_cut's arc in pieces of about h).
std::vector<std::vector<Vec2>> geometry_loops(Params geometry, double h);

/// Node selection: {"type": "point", "at": [x, y]} (the nearest node, which must lie within
/// "tolerance" — default 1e-6 of the body size), {"type": "segment", "from": [..], "to": [..]} (nodes
/// within tolerance of the segment), {"type": "polyline", "points": [[..], ..]} (nodes within tolerance of
/// one of its segments), {"type": "box", "min": [..], "max": [..]}, {"type": "circle",
/// "centre": [..], "radius": r} (nodes within tolerance of the circle), {"type": "all"}.
/// An empty selection is an error.
std::vector<Index> select_nodes(Params select, const std::vector<Vec2>& nodes);

/// A body's builder: reads the body (its case-file object) and builds the model; each model's public header
/// declares its own, and the app layer's registry (model_registry.hpp) maps the "type" strings to them.
using ModelBuilder = std::function<std::unique_ptr<PhysicsModel>(Params body, const CaseContext&)>;

}  // namespace lagfsi
