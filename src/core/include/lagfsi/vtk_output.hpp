#pragma once
/// @file vtk_output.hpp
/// ParaView output: one .pvd time series per body, one .vtu (unstructured grid, VTK XML, binary appended,
/// zlib-compressed) per output step; polylines (rigid walls, shells) go to .vtp (VTK XML PolyData, same
/// encoding). The .pvd is rewritten (to a temporary file, then renamed) after each
/// step so that it is a complete, valid file whenever the run stops.
#include <lagfsi/mesh.hpp>
#include <lagfsi/state_archive.hpp>
#include <lagfsi/types.hpp>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace lagfsi {

/// A point or cell field: n_components values per point (or per cell), point after point.
struct Field {
  std::string name;
  int n_components = 1;
  std::vector<double> values;
};

/// What one .vtu holds. Cells are triangles of `order` (1: VTK_TRIANGLE, 2: VTK_QUADRATIC_TRIANGLE,
/// 3: VTK_LAGRANGE_TRIANGLE); a mesh with zero cells and `vertices_as_cells` = true writes each point as a
/// VTK_VERTEX (particle clouds).
struct VtuData {
  const TriMesh* mesh = nullptr;  ///< connectivity and order; its nodes are ignored if points given
  std::vector<Vec2> points;       ///< current positions (empty: use mesh->nodes)
  std::vector<Field> point_fields;
  std::vector<Field> cell_fields;
  bool vertices_as_cells = false;
};

/// Writes VTK XML unstructured grid file `path` (throws std::invalid_argument for inconsistent data,
/// std::runtime_error on I/O failure).
void write_vtu(const std::filesystem::path& path, const VtuData& data);

/// What one .vtp holds: polylines through `points`. Each entry of `lines` is one polyline (a cell of the
/// PolyData's Lines) through the listed point indices, at least 2 of them (repeat the first index at the
/// end to close it); cell fields have one tuple per line. With no lines, each point is written as a vertex
/// cell (VTK_VERTEX, in the PolyData's Verts) and cell fields have one tuple per point.
struct VtpData {
  std::vector<Vec2> points;
  std::vector<std::vector<Index>> lines;
  std::vector<Field> point_fields;
  std::vector<Field> cell_fields;
};

/// Writes VTK XML PolyData file `path`, with the conventions of write_vtu (throws std::invalid_argument
/// for inconsistent data, std::runtime_error on I/O failure).
void write_vtp(const std::filesystem::path& path, const VtpData& data);

/// A time series: `<dir>/<name>.pvd` referencing `<dir>/<name>/<name>_NNNNN.vtu` (or `.vtp`).
class PvdSeries {
 public:
  PvdSeries(std::filesystem::path dir, std::string name);
  /// Writes the .vtu for time t and rewrites the .pvd atomically.
  void write(double t, const VtuData& data);
  /// One process's piece of a step written over `processes` MPI processes: `<name>_NNNNN_pK.vtu` (K = `process`);
  /// process 0 also writes `<name>_NNNNN.pvtu`, which lists every process's piece with the fields of `piece` (all
  /// processes give the same fields), and rewrites the .pvd, whose entry is the .pvtu.
  void write_piece(double t, const VtuData& piece, int process, int processes);
  /// Same, writing `<name>_NNNNN.vtp`.
  void write(double t, const VtpData& data);
  int steps_written() const { return static_cast<int>(entries_.size()); }
  std::filesystem::path pvd_path() const;
  /// Checkpoints: the entries written so far; reading them back rewrites the .pvd (what a run stopped after
  /// the checkpoint added is dropped) and the next write continues the numbering.
  void serialize(StateArchive& ar);

 private:
  std::filesystem::path dir_;
  std::string name_;
  std::vector<std::pair<double, std::string>> entries_;
};

/// Checkpoints of a series a model creates at its first output (null before): whether it exists, then its
/// entries; reading creates it in `dir` with `name` when the checkpoint had one.
void serialize_series(StateArchive& ar, std::unique_ptr<PvdSeries>& series, const std::filesystem::path& dir,
                      const std::string& name);

}  // namespace lagfsi
