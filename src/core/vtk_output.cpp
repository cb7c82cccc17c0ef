/// @file vtk_output.cpp
/// ParaView output (see vtk_output.hpp): VTK XML unstructured grids and polydata written by
/// vtkXMLUnstructuredGridWriter / vtkXMLPolyDataWriter (binary, appended, raw i.e. not base64-encoded,
/// zlib-compressed), and the .pvd collection file written by hand.
///
/// Conventions of the written files:
///  - points are 3D with z = 0;
///  - a field with 2 components (a 2D vector) is written with 3 components, the third one 0, so that
///    ParaView treats it as a vector (Glyph, Warp By Vector, magnitude colouring); other component
///    counts are written as given;
///  - cells: order 1 -> VTK_TRIANGLE, 2 -> VTK_QUADRATIC_TRIANGLE, 3 -> VTK_LAGRANGE_TRIANGLE with the
///    node order of mesh.hpp, which is VTK's (vertices, then the edge nodes of edges 0-1, 1-2, 2-0, each
///    from its first vertex, then the interior node), so connectivity is written unchanged;
///  - polydata (.vtp): one polyline cell (Lines) per line, or one VTK_VERTEX (Verts) per point when there
///    are no lines.
#include <lagfsi/output_file.hpp>
#include <lagfsi/vtk_output.hpp>

#include <lagfsi/mpi_run.hpp>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>
#include <vtkXMLWriter.h>

#include <cerrno>
#include <cstdio>
#include <stdexcept>
#include <system_error>

namespace lagfsi {

namespace fs = std::filesystem;

namespace {

/// Creates the parent directory of `path` if needed; throws std::runtime_error naming it on failure.
void ensure_parent_directory(const fs::path& path) {
  const fs::path parent = path.parent_path();
  if (parent.empty()) return;
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec || !fs::is_directory(parent))
    throw OutputError(parent.string(), ec ? "cannot create the folder: " + ec.message() : "not a folder");
}

/// vtkPoints holding `points` with z = 0.
vtkSmartPointer<vtkPoints> make_points(const std::vector<Vec2>& points) {
  const auto np = static_cast<vtkIdType>(points.size());
  vtkNew<vtkDoubleArray> coords;
  coords->SetNumberOfComponents(3);
  coords->SetNumberOfTuples(np);
  double* xyz = coords->GetPointer(0);
  for (vtkIdType i = 0; i < np; ++i) {
    const Vec2& p = points[static_cast<size_t>(i)];
    xyz[3 * i] = p.x();
    xyz[3 * i + 1] = p.y();
    xyz[3 * i + 2] = 0.0;
  }
  auto vtk_points = vtkSmartPointer<vtkPoints>::New();
  vtk_points->SetData(coords);
  return vtk_points;
}

/// A vtkDoubleArray holding `field` for `n` points or cells (2-component fields padded to 3); `caller`
/// prefixes error messages.
vtkSmartPointer<vtkDoubleArray> make_array(const Field& field, vtkIdType n, const char* where, const char* caller) {
  if (field.n_components < 1)
    throw std::invalid_argument(std::string(caller) + ": field '" + field.name + "' has " +
                                std::to_string(field.n_components) + " components");
  const auto nc = static_cast<vtkIdType>(field.n_components);
  if (static_cast<vtkIdType>(field.values.size()) != nc * n)
    throw std::invalid_argument(std::string(caller) + ": " + where + " field '" + field.name + "' has " +
                                std::to_string(field.values.size()) + " values, expected " + std::to_string(nc * n));
  const vtkIdType out_nc = nc == 2 ? 3 : nc;
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(field.name.c_str());
  array->SetNumberOfComponents(static_cast<int>(out_nc));
  array->SetNumberOfTuples(n);
  double* out = array->GetPointer(0);
  for (vtkIdType i = 0; i < n; ++i) {
    for (vtkIdType c = 0; c < nc; ++c) out[i * out_nc + c] = field.values[static_cast<size_t>(i * nc + c)];
    if (nc == 2) out[i * out_nc + 2] = 0.0;
  }
  return array;
}

/// Adds the point and cell fields to `dataset` (np points, nc cells).
void add_fields(vtkDataSet* dataset, const std::vector<Field>& point_fields, const std::vector<Field>& cell_fields,
                vtkIdType np, vtkIdType nc, const char* caller) {
  for (const Field& f : point_fields) dataset->GetPointData()->AddArray(make_array(f, np, "point", caller));
  for (const Field& f : cell_fields) dataset->GetCellData()->AddArray(make_array(f, nc, "cell", caller));
}

/// Writes `input` to `path` with `writer` (binary appended raw, zlib), creating the parent directory. A
/// failure throws OutputError naming the file, with the system's reason when there is one; VTK's own error
/// log (several coloured lines on stderr) is switched off: the caller reports the error in one line.
void write_xml(vtkXMLWriter* writer, vtkDataObject* input, const fs::path& path) {
  ensure_parent_directory(path);
  vtkObject::GlobalWarningDisplayOff();
  writer->SetFileName(path.string().c_str());
  writer->SetInputData(input);
  writer->SetDataModeToAppended();
  writer->SetEncodeAppendedData(false);
  writer->SetCompressorTypeToZLib();
  errno = 0;
  const int ok = writer->Write();
  const int err = errno;
  const unsigned long code = writer->GetErrorCode();
  if (!ok || code != vtkErrorCode::NoError) {
    std::string reason = err != 0 ? errno_reason(err) : std::string();
    if (reason.empty() && code == vtkErrorCode::OutOfDiskSpaceError) reason = "out of disk space";
    if (reason.empty() && code == vtkErrorCode::CannotOpenFileError) reason = "cannot open the file";
    if (reason.empty()) reason = "VTK error code " + std::to_string(code);
    throw OutputError(path.string(), reason);
  }
}

/// Offsets 0, 1, ..., n and connectivity 0, ..., n-1: one vertex cell per point.
void fill_vertex_cells(vtkIdType n, vtkIdTypeArray* offsets, vtkIdTypeArray* connectivity) {
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(n);
  for (vtkIdType i = 0; i <= n; ++i) offsets->SetValue(i, i);
  for (vtkIdType i = 0; i < n; ++i) connectivity->SetValue(i, i);
}

int vtk_cell_type(int order) {
  switch (order) {
    case 1:
      return VTK_TRIANGLE;
    case 2:
      return VTK_QUADRATIC_TRIANGLE;
    case 3:
      return VTK_LAGRANGE_TRIANGLE;
    default:
      throw std::invalid_argument("write_vtu: unsupported triangle order " + std::to_string(order));
  }
}

/// XML attribute value with the five special characters escaped.
std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// `<name>_NNNNN<extension>`, the file of step `step` of series `name`.
std::string step_file_name(const std::string& name, int step, const char* extension) {
  char suffix[64];
  std::snprintf(suffix, sizeof suffix, "_%05d%s", step, extension);
  return name + suffix;
}

/// Rewrites the whole .pvd `pvd` listing `entries` (time, file relative to the .pvd) into a temporary
/// file, then renames it over the old one (atomic on POSIX).
void rewrite_pvd(const fs::path& pvd, const std::vector<std::pair<double, std::string>>& entries) {
  std::string text =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  char time[32];
  for (const auto& [time_value, file] : entries) {
    std::snprintf(time, sizeof time, "%.17g", time_value);
    text += std::string("    <DataSet timestep=\"") + time + "\" group=\"\" part=\"0\" file=\"" + xml_escape(file) +
            "\"/>\n";
  }
  text += "  </Collection>\n</VTKFile>\n";
  write_file_atomic(pvd, text);
}

}  // namespace

void write_vtu(const fs::path& path, const VtuData& data) {
  // ------------------------------------------------------------ points
  const std::vector<Vec2>* points = &data.points;
  if (points->empty() && data.mesh) points = &data.mesh->nodes;
  const auto np = static_cast<vtkIdType>(points->size());
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(make_points(*points));

  // ------------------------------------------------------------ cells
  const Index ne = data.mesh ? data.mesh->num_elements() : 0;
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  int cell_type = VTK_VERTEX;
  vtkIdType nc = 0;
  if (ne > 0) {
    if (data.vertices_as_cells) throw std::invalid_argument("write_vtu: vertices_as_cells needs a mesh without cells");
    const TriMesh& mesh = *data.mesh;
    cell_type = vtk_cell_type(mesh.order);
    const int npe = mesh.nodes_per_element();
    if (mesh.conn.size() != static_cast<size_t>(ne) * static_cast<size_t>(npe))
      throw std::invalid_argument("write_vtu: connectivity size is not a multiple of " + std::to_string(npe));
    nc = ne;
    offsets->SetNumberOfValues(nc + 1);
    connectivity->SetNumberOfValues(nc * npe);
    for (vtkIdType e = 0; e <= nc; ++e) offsets->SetValue(e, e * npe);
    for (size_t k = 0; k < mesh.conn.size(); ++k) {
      const Index node = mesh.conn[k];
      if (node < 0 || node >= np)
        throw std::invalid_argument("write_vtu: element node " + std::to_string(node) + " out of range (" +
                                    std::to_string(np) + " points)");
      connectivity->SetValue(static_cast<vtkIdType>(k), node);
    }
  } else if (data.vertices_as_cells) {
    nc = np;
    fill_vertex_cells(nc, offsets, connectivity);
  } else {
    offsets->SetNumberOfValues(1);
    offsets->SetValue(0, 0);
  }
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets.Get(), connectivity.Get());
  grid->SetCells(cell_type, cells);

  add_fields(grid, data.point_fields, data.cell_fields, np, nc, "write_vtu");
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  write_xml(writer, grid, path);
}

void write_vtp(const fs::path& path, const VtpData& data) {
  const auto np = static_cast<vtkIdType>(data.points.size());
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(make_points(data.points));

  vtkNew<vtkIdTypeArray> offsets, connectivity;
  vtkIdType nc = 0;
  if (!data.lines.empty()) {
    nc = static_cast<vtkIdType>(data.lines.size());
    vtkIdType total = 0;
    for (size_t l = 0; l < data.lines.size(); ++l) {
      if (data.lines[l].size() < 2)
        throw std::invalid_argument("write_vtp: line " + std::to_string(l) + " has " +
                                    std::to_string(data.lines[l].size()) + " points, at least 2 needed");
      total += static_cast<vtkIdType>(data.lines[l].size());
    }
    offsets->SetNumberOfValues(nc + 1);
    connectivity->SetNumberOfValues(total);
    vtkIdType k = 0;
    offsets->SetValue(0, 0);
    for (size_t l = 0; l < data.lines.size(); ++l) {
      for (const Index node : data.lines[l]) {
        if (node < 0 || node >= np)
          throw std::invalid_argument("write_vtp: line " + std::to_string(l) + " node " + std::to_string(node) +
                                      " out of range (" + std::to_string(np) + " points)");
        connectivity->SetValue(k++, node);
      }
      offsets->SetValue(static_cast<vtkIdType>(l) + 1, k);
    }
    vtkNew<vtkCellArray> cells;
    cells->SetData(offsets.Get(), connectivity.Get());
    poly->SetLines(cells);
  } else {
    nc = np;
    fill_vertex_cells(nc, offsets, connectivity);
    vtkNew<vtkCellArray> cells;
    cells->SetData(offsets.Get(), connectivity.Get());
    poly->SetVerts(cells);
  }

  add_fields(poly, data.point_fields, data.cell_fields, np, nc, "write_vtp");
  vtkNew<vtkXMLPolyDataWriter> writer;
  write_xml(writer, poly, path);
}

PvdSeries::PvdSeries(fs::path dir, std::string name) : dir_(std::move(dir)), name_(std::move(name)) {}

fs::path PvdSeries::pvd_path() const { return dir_ / (name_ + ".pvd"); }

void PvdSeries::write(double t, const VtuData& data) {
  const std::string file = step_file_name(name_, steps_written(), ".vtu");
  write_vtu(dir_ / name_ / file, data);
  // Relative to the .pvd, with '/' separators whatever the platform.
  entries_.emplace_back(t, name_ + "/" + file);
  rewrite_pvd(pvd_path(), entries_);
}

void PvdSeries::write_piece(double t, const VtuData& piece, int process, int processes) {
  const std::string stem = step_file_name(name_, steps_written(), "");
  const auto piece_file = [&](int k) { return stem + "_p" + std::to_string(k) + ".vtu"; };
  write_vtu(dir_ / name_ / piece_file(process), piece);
  entries_.emplace_back(t, name_ + "/" + stem + ".pvtu");
  if (process != 0) return;
  // The parallel file: the arrays as write_vtu writes them (doubles; a 2-component field padded to 3).
  const auto arrays = [](const std::vector<Field>& fields) {
    std::string text;
    for (const Field& f : fields)
      text += "      <PDataArray type=\"Float64\" Name=\"" + xml_escape(f.name) + "\" NumberOfComponents=\"" +
              std::to_string(f.n_components == 2 ? 3 : f.n_components) + "\"/>\n";
    return text;
  };
  std::string text =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      "  <PUnstructuredGrid GhostLevel=\"0\">\n    <PPointData>\n" +
      arrays(piece.point_fields) + "    </PPointData>\n    <PCellData>\n" + arrays(piece.cell_fields) +
      "    </PCellData>\n    <PPoints>\n      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n"
      "    </PPoints>\n";
  for (int k = 0; k < processes; ++k) text += "    <Piece Source=\"" + xml_escape(piece_file(k)) + "\"/>\n";
  text += "  </PUnstructuredGrid>\n</VTKFile>\n";
  write_file_atomic(dir_ / name_ / (stem + ".pvtu"), text);
  rewrite_pvd(pvd_path(), entries_);
}

void PvdSeries::write(double t, const VtpData& data) {
  const std::string file = step_file_name(name_, steps_written(), ".vtp");
  write_vtp(dir_ / name_ / file, data);
  entries_.emplace_back(t, name_ + "/" + file);
  rewrite_pvd(pvd_path(), entries_);
}

void PvdSeries::serialize(StateArchive& ar) {
  ar.section("pvd " + name_);
  ar.io(entries_);
  if (ar.loading() && mpi_run::writer()) rewrite_pvd(pvd_path(), entries_);  // an MPI run: process 0's file
}

void serialize_series(StateArchive& ar, std::unique_ptr<PvdSeries>& series, const fs::path& dir,
                      const std::string& name) {
  bool exists = series != nullptr;
  ar.io(exists);
  if (!exists) {
    if (ar.loading()) series.reset();
    return;
  }
  if (ar.loading()) series = std::make_unique<PvdSeries>(dir, name);
  series->serialize(ar);
}

}  // namespace lagfsi
