// Unit tests of the ParaView output (vtk_output.hpp): .vtu files are read back with VTK's own reader and
// checked against the data written (points, cell types, connectivity, fields); for T6/T10 the curved
// geometry is evaluated by VTK's cell at interior parametric points and compared with the exact
// polynomial map, which checks that mesh.hpp's node order is the one VTK expects. .vtp polyline files are
// read back with vtkXMLPolyDataReader. The .pvd is parsed with VTK's XML parser.
#include <lagfsi/vtk_output.hpp>

#include <gtest/gtest.h>

#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUtilities.h>

#include <unistd.h>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

using namespace lagfsi;
namespace fs = std::filesystem;

namespace {

// A fresh, empty temporary directory removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name =
        "lagfsi_test_vtk_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name();
    for (char& c : name)
      if (c == '/') c = '_';  // parameterized test names contain '/'
    path_ = fs::temp_directory_path() / name;
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// Polynomial map of degree `order` (exactly representable by a triangle of that order).
Vec2 curved_map(const Vec2& p, int order) {
  Vec2 q = 2.0 * p + Vec2(0.5, -1.0);
  if (order >= 2) q += Vec2(0.1 * p.y() * p.y() + 0.05 * p.x() * p.y(), 0.2 * p.x() * p.y() - 0.1 * p.x() * p.x());
  if (order >= 3) q += Vec2(0.07 * p.x() * p.x() * p.y(), -0.04 * p.y() * p.y() * p.y());
  return q;
}

// Position of local node `k` of a triangle of `order` in its parametric coordinates (r, s), following
// the numbering documented in mesh.hpp: vertices, then order-1 nodes per edge 0-1, 1-2, 2-0 (from the
// edge's first vertex), then interior nodes (only the centroid for order <= 3).
Vec2 local_node(int order, int k) {
  const Vec2 v[3] = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  if (k < 3) return v[k];
  const int per_edge = order - 1;
  if (k < 3 + 3 * per_edge) {
    const int edge = (k - 3) / per_edge, i = (k - 3) % per_edge + 1;
    return v[edge] + (double(i) / order) * (v[(edge + 1) % 3] - v[edge]);
  }
  return Vec2(1.0 / 3.0, 1.0 / 3.0);
}

// Two triangles (0,0)-(1,0)-(1,1) and (0,0)-(1,1)-(0,1), of the given order, nodes mapped by curved_map.
// Returns the mesh and, per element, its affine parametric map (origin, e1, e2) before curving.
struct TestMesh {
  TriMesh mesh;
  std::vector<std::array<Vec2, 3>> affine;  // vertex 0, vertex 1, vertex 2 of the straight triangle
};

TestMesh two_triangles(int order) {
  TestMesh out;
  out.mesh.order = order;
  const std::array<Vec2, 3> tri[2] = {{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1)}, {Vec2(0, 0), Vec2(1, 1), Vec2(0, 1)}};
  std::map<std::pair<long, long>, Index> ids;  // node deduplication on a fine lattice
  for (const auto& t : tri) {
    out.affine.push_back(t);
    for (int k = 0; k < TriMesh::nodes_per_element(order); ++k) {
      const Vec2 rs = local_node(order, k);
      const Vec2 p = t[0] + rs.x() * (t[1] - t[0]) + rs.y() * (t[2] - t[0]);
      const std::pair<long, long> key{std::lround(p.x() * 3000), std::lround(p.y() * 3000)};
      auto it = ids.find(key);
      if (it == ids.end()) {
        it = ids.emplace(key, out.mesh.num_nodes()).first;
        out.mesh.nodes.push_back(curved_map(p, order));
      }
      out.mesh.conn.push_back(it->second);
    }
  }
  return out;
}

vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const fs::path& path) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.string().c_str());
  reader->Update();
  vtkSmartPointer<vtkUnstructuredGrid> grid = reader->GetOutput();
  return grid;
}

vtkSmartPointer<vtkPolyData> read_vtp(const fs::path& path) {
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.string().c_str());
  reader->Update();
  vtkSmartPointer<vtkPolyData> poly = reader->GetOutput();
  return poly;
}

// Point ids of cell `c` of `poly`.
std::vector<vtkIdType> cell_point_ids(vtkPolyData* poly, vtkIdType c) {
  vtkNew<vtkIdList> ids;
  poly->GetCellPoints(c, ids);
  std::vector<vtkIdType> out;
  for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) out.push_back(ids->GetId(k));
  return out;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

int expected_vtk_type(int order) {
  return order == 1 ? VTK_TRIANGLE : order == 2 ? VTK_QUADRATIC_TRIANGLE : VTK_LAGRANGE_TRIANGLE;
}

}  // namespace

class VtuOrder : public ::testing::TestWithParam<int> {};

INSTANTIATE_TEST_SUITE_P(VtkOutput, VtuOrder, ::testing::Values(1, 2, 3), [](const auto& info) {
  // (GCC 12 warns -Wrestrict on "T" + std::to_string(...); append instead.)
  std::string name = "T";
  name += std::to_string((info.param + 1) * (info.param + 2) / 2);
  return name;
});

TEST_P(VtuOrder, WritesMeshAndFieldsThatVtkReadsBack) {
  const int order = GetParam();
  TempDir tmp;
  const TestMesh tm = two_triangles(order);
  const TriMesh& mesh = tm.mesh;
  const Index np = mesh.num_nodes();
  ASSERT_EQ(np, order == 1 ? 4 : order == 2 ? 9 : 16);

  Field scalar{"pressure", 1, {}}, vector{"velocity", 2, {}}, cellf{"element_id", 1, {}};
  for (Index i = 0; i < np; ++i) {
    const Vec2& x = mesh.nodes[i];
    scalar.values.push_back(x.x() + 2.0 * x.y());
    vector.values.push_back(x.y());
    vector.values.push_back(-x.x() + 0.5);
  }
  for (Index e = 0; e < mesh.num_elements(); ++e) cellf.values.push_back(10.0 + e);

  VtuData data;
  data.mesh = &mesh;
  data.point_fields = {scalar, vector};
  data.cell_fields = {cellf};
  const fs::path file = tmp.path() / "sub" / "mesh.vtu";  // parent directory created by write_vtu
  write_vtu(file, data);

  // Raw file: XML header, binary appended and zlib-compressed.
  const std::string text = read_text(file);
  EXPECT_EQ(text.rfind("<?xml", 0) == 0 || text.rfind("<VTKFile", 0) == 0, true);
  EXPECT_NE(text.find("type=\"UnstructuredGrid\""), std::string::npos);
  EXPECT_NE(text.find("vtkZLibDataCompressor"), std::string::npos);
  EXPECT_NE(text.find("<AppendedData encoding=\"raw\">"), std::string::npos);

  auto grid = read_vtu(file);
  ASSERT_TRUE(grid);
  ASSERT_EQ(grid->GetNumberOfPoints(), np);
  ASSERT_EQ(grid->GetNumberOfCells(), 2);
  for (Index i = 0; i < np; ++i) {
    double p[3];
    grid->GetPoint(i, p);
    EXPECT_DOUBLE_EQ(p[0], mesh.nodes[i].x());
    EXPECT_DOUBLE_EQ(p[1], mesh.nodes[i].y());
    EXPECT_EQ(p[2], 0.0);
  }
  for (vtkIdType c = 0; c < 2; ++c) {
    EXPECT_EQ(grid->GetCellType(c), expected_vtk_type(order));
    vtkCell* cell = grid->GetCell(c);
    ASSERT_EQ(cell->GetNumberOfPoints(), mesh.nodes_per_element());
    for (int k = 0; k < mesh.nodes_per_element(); ++k)
      EXPECT_EQ(cell->GetPointId(k), mesh.element(static_cast<Index>(c))[k]);
  }

  vtkDataArray* s = grid->GetPointData()->GetArray("pressure");
  vtkDataArray* v = grid->GetPointData()->GetArray("velocity");
  vtkDataArray* ce = grid->GetCellData()->GetArray("element_id");
  ASSERT_TRUE(s && v && ce);
  EXPECT_EQ(s->GetNumberOfComponents(), 1);
  EXPECT_EQ(v->GetNumberOfComponents(), 3);  // 2D vectors padded with z = 0
  EXPECT_EQ(ce->GetNumberOfComponents(), 1);
  for (Index i = 0; i < np; ++i) {
    const Vec2& x = mesh.nodes[i];
    EXPECT_EQ(s->GetComponent(i, 0), x.x() + 2.0 * x.y());
    EXPECT_EQ(v->GetComponent(i, 0), x.y());
    EXPECT_EQ(v->GetComponent(i, 1), -x.x() + 0.5);
    EXPECT_EQ(v->GetComponent(i, 2), 0.0);
  }
  EXPECT_EQ(ce->GetComponent(0, 0), 10.0);
  EXPECT_EQ(ce->GetComponent(1, 0), 11.0);
}

TEST_P(VtuOrder, VtkInterpolatesTheCurvedGeometryExactly) {
  // VTK's cell interpolation of the written nodes must reproduce the polynomial map: this fails if the
  // node order of mesh.hpp differed from VTK's for the cell type used.
  const int order = GetParam();
  TempDir tmp;
  const TestMesh tm = two_triangles(order);
  VtuData data;
  data.mesh = &tm.mesh;
  write_vtu(tmp.path() / "curved.vtu", data);
  auto grid = read_vtu(tmp.path() / "curved.vtu");
  ASSERT_EQ(grid->GetNumberOfCells(), 2);
  const double samples[][2] = {{0.2, 0.3}, {0.6, 0.1}, {0.1, 0.7}, {1.0 / 3.0, 1.0 / 3.0}, {0.45, 0.45}};
  for (vtkIdType c = 0; c < 2; ++c) {
    vtkCell* cell = grid->GetCell(c);
    std::vector<double> weights(static_cast<size_t>(cell->GetNumberOfPoints()));
    for (const auto& rs : samples) {
      double pcoords[3] = {rs[0], rs[1], 0.0}, x[3];
      int sub_id = 0;
      cell->EvaluateLocation(sub_id, pcoords, x, weights.data());
      const auto& t = tm.affine[static_cast<size_t>(c)];
      const Vec2 straight = t[0] + rs[0] * (t[1] - t[0]) + rs[1] * (t[2] - t[0]);
      const Vec2 expected = curved_map(straight, order);
      EXPECT_NEAR(x[0], expected.x(), 1e-12) << "cell " << c << " at (" << rs[0] << ", " << rs[1] << ")";
      EXPECT_NEAR(x[1], expected.y(), 1e-12) << "cell " << c << " at (" << rs[0] << ", " << rs[1] << ")";
    }
  }
}

TEST(VtkOutput, UsesGivenPointsInsteadOfMeshNodes) {
  TempDir tmp;
  const TestMesh tm = two_triangles(1);
  VtuData data;
  data.mesh = &tm.mesh;
  for (const Vec2& p : tm.mesh.nodes) data.points.push_back(p + Vec2(100.0, -3.0));
  write_vtu(tmp.path() / "moved.vtu", data);
  auto grid = read_vtu(tmp.path() / "moved.vtu");
  ASSERT_EQ(grid->GetNumberOfPoints(), 4);
  for (vtkIdType i = 0; i < 4; ++i) {
    double p[3];
    grid->GetPoint(i, p);
    EXPECT_EQ(p[0], tm.mesh.nodes[static_cast<size_t>(i)].x() + 100.0);
    EXPECT_EQ(p[1], tm.mesh.nodes[static_cast<size_t>(i)].y() - 3.0);
  }
}

TEST(VtkOutput, ParticleCloudAsVertexCells) {
  TempDir tmp;
  TriMesh empty;  // no cells
  VtuData data;
  data.mesh = &empty;
  data.points = {Vec2(0, 0), Vec2(1, 0.5), Vec2(2, 1), Vec2(-1, 3), Vec2(0.25, 0.75)};
  data.vertices_as_cells = true;
  data.point_fields = {Field{"id", 1, {0, 1, 2, 3, 4}}};
  data.cell_fields = {Field{"cell_id", 1, {5, 6, 7, 8, 9}}};
  write_vtu(tmp.path() / "cloud.vtu", data);
  auto grid = read_vtu(tmp.path() / "cloud.vtu");
  ASSERT_EQ(grid->GetNumberOfPoints(), 5);
  ASSERT_EQ(grid->GetNumberOfCells(), 5);
  for (vtkIdType c = 0; c < 5; ++c) {
    EXPECT_EQ(grid->GetCellType(c), VTK_VERTEX);
    ASSERT_EQ(grid->GetCell(c)->GetNumberOfPoints(), 1);
    EXPECT_EQ(grid->GetCell(c)->GetPointId(0), c);
    EXPECT_EQ(grid->GetCellData()->GetArray("cell_id")->GetComponent(c, 0), 5.0 + c);
  }

  // Without a mesh at all, and without vertex cells: points only.
  VtuData bare;
  bare.points = data.points;
  write_vtu(tmp.path() / "bare.vtu", bare);
  auto grid2 = read_vtu(tmp.path() / "bare.vtu");
  EXPECT_EQ(grid2->GetNumberOfPoints(), 5);
  EXPECT_EQ(grid2->GetNumberOfCells(), 0);
}

TEST(VtkOutput, InconsistentDataIsRejected) {
  TempDir tmp;
  const TestMesh tm = two_triangles(2);
  VtuData data;
  data.mesh = &tm.mesh;
  data.point_fields = {Field{"short", 1, {1.0, 2.0}}};
  EXPECT_THROW(write_vtu(tmp.path() / "a.vtu", data), std::invalid_argument);
  data.point_fields.clear();
  data.cell_fields = {Field{"v", 2, {1.0, 2.0, 3.0}}};  // 2 cells x 2 components needed
  EXPECT_THROW(write_vtu(tmp.path() / "b.vtu", data), std::invalid_argument);
  data.cell_fields.clear();
  data.points = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};  // fewer points than the connectivity uses
  EXPECT_THROW(write_vtu(tmp.path() / "c.vtu", data), std::invalid_argument);
}

TEST(VtkOutput, IoFailureThrowsRuntimeErrorWithThePath) {
  TempDir tmp;
  const fs::path blocker = tmp.path() / "not_a_directory";
  std::ofstream(blocker) << "x";
  const TestMesh tm = two_triangles(1);
  VtuData data;
  data.mesh = &tm.mesh;
  try {
    write_vtu(blocker / "out.vtu", data);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not_a_directory"), std::string::npos) << e.what();
  }
  PvdSeries series(blocker, "body");
  try {
    series.write(0.0, data);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not_a_directory"), std::string::npos) << e.what();
  }
}

TEST(VtkOutput, PvdSeriesListsEveryStep) {
  TempDir tmp;
  const fs::path dir = tmp.path() / "out" / "run1";  // created on the first write
  const TestMesh tm = two_triangles(3);
  PvdSeries series(dir, "solid");
  EXPECT_EQ(series.pvd_path(), dir / "solid.pvd");
  EXPECT_EQ(series.steps_written(), 0);

  const double times[3] = {0.0, 1.0 / 3.0, 2.0e-3 + 1e-15};
  for (int step = 0; step < 3; ++step) {
    VtuData data;
    data.mesh = &tm.mesh;
    data.point_fields = {Field{"step", 1, std::vector<double>(tm.mesh.nodes.size(), double(step))}};
    series.write(times[step], data);
    EXPECT_EQ(series.steps_written(), step + 1);

    // After every step the .pvd is complete and lists exactly the steps written so far.
    const std::string text = read_text(series.pvd_path());
    ASSERT_GE(text.size(), 11u);
    EXPECT_EQ(text.substr(text.find_last_not_of(" \n\r") - 9, 10), "</VTKFile>");
    EXPECT_FALSE(fs::exists(dir / "solid.pvd.tmp"));

    vtkSmartPointer<vtkXMLDataElement> root;
    root.TakeReference(vtkXMLUtilities::ReadElementFromFile(series.pvd_path().string().c_str()));
    ASSERT_TRUE(root) << "not well-formed XML:\n" << text;
    EXPECT_STREQ(root->GetName(), "VTKFile");
    ASSERT_STREQ(root->GetAttribute("type"), "Collection");
    vtkXMLDataElement* collection = root->FindNestedElementWithName("Collection");
    ASSERT_TRUE(collection);
    ASSERT_EQ(collection->GetNumberOfNestedElements(), step + 1);
    for (int k = 0; k <= step; ++k) {
      vtkXMLDataElement* ds = collection->GetNestedElement(k);
      EXPECT_STREQ(ds->GetName(), "DataSet");
      // Full precision: the time must read back bit-identical.
      EXPECT_EQ(std::strtod(ds->GetAttribute("timestep"), nullptr), times[k]);
      char expected_file[64];
      std::snprintf(expected_file, sizeof expected_file, "solid/solid_%05d.vtu", k);
      EXPECT_STREQ(ds->GetAttribute("file"), expected_file);
      // The relative path resolves from the .pvd's directory to the data of that step.
      auto grid = read_vtu(dir / ds->GetAttribute("file"));
      ASSERT_EQ(grid->GetNumberOfPoints(), tm.mesh.num_nodes());
      EXPECT_EQ(grid->GetPointData()->GetArray("step")->GetComponent(0, 0), double(k));
    }
  }
}

// ---------------------------------------------------------------------------------------------- .vtp

TEST(VtpOutput, PolylinesAndFieldsThatVtkReadsBack) {
  TempDir tmp;
  VtpData data;
  // An open wall of 4 points and a closed triangle (first point repeated at the end).
  data.points = {Vec2(0, 0), Vec2(1, 0), Vec2(2, 0.5), Vec2(3, 0.5), Vec2(0, 2), Vec2(1, 2), Vec2(0.5, 3)};
  data.lines = {{0, 1, 2, 3}, {4, 5, 6, 4}};
  Field scalar{"pressure", 1, {}}, vector{"normal", 2, {}};
  for (const Vec2& x : data.points) {
    scalar.values.push_back(x.x() - 3.0 * x.y());
    vector.values.push_back(x.y() + 0.25);
    vector.values.push_back(-x.x());
  }
  data.point_fields = {scalar, vector};
  data.cell_fields = {Field{"wall_id", 1, {7.0, 8.0}}, Field{"force", 2, {1.0, 2.0, 3.0, 4.0}}};
  const fs::path file = tmp.path() / "sub" / "walls.vtp";  // parent directory created by write_vtp
  write_vtp(file, data);

  const std::string text = read_text(file);
  EXPECT_NE(text.find("type=\"PolyData\""), std::string::npos);
  EXPECT_NE(text.find("vtkZLibDataCompressor"), std::string::npos);
  EXPECT_NE(text.find("<AppendedData encoding=\"raw\">"), std::string::npos);

  auto poly = read_vtp(file);
  ASSERT_TRUE(poly);
  ASSERT_EQ(poly->GetNumberOfPoints(), 7);
  for (vtkIdType i = 0; i < 7; ++i) {
    double p[3];
    poly->GetPoint(i, p);
    EXPECT_EQ(p[0], data.points[static_cast<size_t>(i)].x());
    EXPECT_EQ(p[1], data.points[static_cast<size_t>(i)].y());
    EXPECT_EQ(p[2], 0.0);
  }
  EXPECT_EQ(poly->GetNumberOfVerts(), 0);
  ASSERT_EQ(poly->GetNumberOfLines(), 2);
  ASSERT_EQ(poly->GetNumberOfCells(), 2);
  for (vtkIdType c = 0; c < 2; ++c) {
    EXPECT_EQ(poly->GetCellType(c), VTK_POLY_LINE);
    const auto& line = data.lines[static_cast<size_t>(c)];
    EXPECT_EQ(cell_point_ids(poly, c), std::vector<vtkIdType>(line.begin(), line.end()));
  }

  vtkDataArray* s = poly->GetPointData()->GetArray("pressure");
  vtkDataArray* v = poly->GetPointData()->GetArray("normal");
  vtkDataArray* id = poly->GetCellData()->GetArray("wall_id");
  vtkDataArray* f = poly->GetCellData()->GetArray("force");
  ASSERT_TRUE(s && v && id && f);
  EXPECT_EQ(s->GetNumberOfComponents(), 1);
  EXPECT_EQ(v->GetNumberOfComponents(), 3);  // 2D vectors padded with z = 0
  EXPECT_EQ(f->GetNumberOfComponents(), 3);
  for (vtkIdType i = 0; i < 7; ++i) {
    const Vec2& x = data.points[static_cast<size_t>(i)];
    EXPECT_EQ(s->GetComponent(i, 0), x.x() - 3.0 * x.y());
    EXPECT_EQ(v->GetComponent(i, 0), x.y() + 0.25);
    EXPECT_EQ(v->GetComponent(i, 1), -x.x());
    EXPECT_EQ(v->GetComponent(i, 2), 0.0);
  }
  EXPECT_EQ(id->GetComponent(0, 0), 7.0);
  EXPECT_EQ(id->GetComponent(1, 0), 8.0);
  EXPECT_EQ(f->GetComponent(0, 0), 1.0);
  EXPECT_EQ(f->GetComponent(0, 1), 2.0);
  EXPECT_EQ(f->GetComponent(0, 2), 0.0);
  EXPECT_EQ(f->GetComponent(1, 0), 3.0);
  EXPECT_EQ(f->GetComponent(1, 1), 4.0);
  EXPECT_EQ(f->GetComponent(1, 2), 0.0);
}

TEST(VtpOutput, WithoutLinesEachPointIsAVertex) {
  TempDir tmp;
  VtpData data;
  data.points = {Vec2(0, 0), Vec2(1, 0.5), Vec2(2, 1), Vec2(-1, 3), Vec2(0.25, 0.75)};
  data.point_fields = {Field{"id", 1, {0, 1, 2, 3, 4}}};
  data.cell_fields = {Field{"cell_id", 1, {5, 6, 7, 8, 9}}};  // one per point
  write_vtp(tmp.path() / "cloud.vtp", data);
  auto poly = read_vtp(tmp.path() / "cloud.vtp");
  ASSERT_EQ(poly->GetNumberOfPoints(), 5);
  EXPECT_EQ(poly->GetNumberOfLines(), 0);
  ASSERT_EQ(poly->GetNumberOfVerts(), 5);
  ASSERT_EQ(poly->GetNumberOfCells(), 5);
  for (vtkIdType c = 0; c < 5; ++c) {
    EXPECT_EQ(poly->GetCellType(c), VTK_VERTEX);
    EXPECT_EQ(cell_point_ids(poly, c), std::vector<vtkIdType>{c});
    EXPECT_EQ(poly->GetPointData()->GetArray("id")->GetComponent(c, 0), double(c));
    EXPECT_EQ(poly->GetCellData()->GetArray("cell_id")->GetComponent(c, 0), 5.0 + c);
  }

  // No points at all: a valid, empty file.
  write_vtp(tmp.path() / "empty.vtp", VtpData{});
  auto empty = read_vtp(tmp.path() / "empty.vtp");
  EXPECT_EQ(empty->GetNumberOfPoints(), 0);
  EXPECT_EQ(empty->GetNumberOfCells(), 0);
}

TEST(VtpOutput, InconsistentDataIsRejected) {
  TempDir tmp;
  VtpData data;
  data.points = {Vec2(0, 0), Vec2(1, 0), Vec2(2, 0)};
  data.lines = {{0, 1, 2}, {2, 0}};
  data.point_fields = {Field{"short", 1, {1.0, 2.0}}};
  EXPECT_THROW(write_vtp(tmp.path() / "a.vtp", data), std::invalid_argument);
  data.point_fields.clear();
  data.cell_fields = {Field{"per_point", 1, {1.0, 2.0, 3.0}}};  // 2 lines: one value per line
  EXPECT_THROW(write_vtp(tmp.path() / "b.vtp", data), std::invalid_argument);
  data.cell_fields = {Field{"zero", 0, {}}};
  EXPECT_THROW(write_vtp(tmp.path() / "c.vtp", data), std::invalid_argument);
  data.cell_fields.clear();
  data.lines = {{0, 1, 3}};  // point 3 does not exist
  EXPECT_THROW(write_vtp(tmp.path() / "d.vtp", data), std::invalid_argument);
  data.lines = {{0, -1}};
  EXPECT_THROW(write_vtp(tmp.path() / "e.vtp", data), std::invalid_argument);
  data.lines = {{0, 1}, {2}};  // a polyline needs 2 points
  EXPECT_THROW(write_vtp(tmp.path() / "f.vtp", data), std::invalid_argument);
  data.lines = {{0, 1}, {}};
  EXPECT_THROW(write_vtp(tmp.path() / "g.vtp", data), std::invalid_argument);
  data.lines.clear();
  data.cell_fields = {Field{"per_line", 1, {1.0}}};  // no lines: one value per point (vertex cells)
  EXPECT_THROW(write_vtp(tmp.path() / "h.vtp", data), std::invalid_argument);
  for (const char* name : {"a", "b", "c", "d", "e", "f", "g", "h"})
    EXPECT_FALSE(fs::exists(tmp.path() / (std::string(name) + ".vtp"))) << name;
}

TEST(VtpOutput, IoFailureThrowsRuntimeErrorWithThePath) {
  TempDir tmp;
  const fs::path blocker = tmp.path() / "not_a_directory";
  std::ofstream(blocker) << "x";
  VtpData data;
  data.points = {Vec2(0, 0), Vec2(1, 0)};
  data.lines = {{0, 1}};
  try {
    write_vtp(blocker / "out.vtp", data);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not_a_directory"), std::string::npos) << e.what();
  }
  PvdSeries series(blocker, "wall");
  try {
    series.write(0.0, data);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not_a_directory"), std::string::npos) << e.what();
  }
  EXPECT_EQ(series.steps_written(), 0);
}

TEST(VtpOutput, PvdSeriesListsVtpSteps) {
  TempDir tmp;
  const fs::path dir = tmp.path() / "out" / "run1";  // created on the first write
  PvdSeries series(dir, "wall");
  const double times[3] = {0.0, 0.125, 1.0 / 7.0};
  for (int step = 0; step < 3; ++step) {
    VtpData data;
    data.points = {Vec2(0, step), Vec2(1, step), Vec2(2, step)};
    data.lines = {{0, 1, 2}};
    data.point_fields = {Field{"step", 1, std::vector<double>(3, double(step))}};
    data.cell_fields = {Field{"line_step", 1, {10.0 + step}}};
    series.write(times[step], data);
    EXPECT_EQ(series.steps_written(), step + 1);
    EXPECT_FALSE(fs::exists(dir / "wall.pvd.tmp"));

    vtkSmartPointer<vtkXMLDataElement> root;
    root.TakeReference(vtkXMLUtilities::ReadElementFromFile(series.pvd_path().string().c_str()));
    ASSERT_TRUE(root) << "not well-formed XML:\n" << read_text(series.pvd_path());
    ASSERT_STREQ(root->GetAttribute("type"), "Collection");
    vtkXMLDataElement* collection = root->FindNestedElementWithName("Collection");
    ASSERT_TRUE(collection);
    ASSERT_EQ(collection->GetNumberOfNestedElements(), step + 1);
    for (int k = 0; k <= step; ++k) {
      vtkXMLDataElement* ds = collection->GetNestedElement(k);
      EXPECT_STREQ(ds->GetName(), "DataSet");
      EXPECT_EQ(std::strtod(ds->GetAttribute("timestep"), nullptr), times[k]);
      char expected_file[64];
      std::snprintf(expected_file, sizeof expected_file, "wall/wall_%05d.vtp", k);
      EXPECT_STREQ(ds->GetAttribute("file"), expected_file);
      auto poly = read_vtp(dir / ds->GetAttribute("file"));
      ASSERT_EQ(poly->GetNumberOfPoints(), 3);
      ASSERT_EQ(poly->GetNumberOfLines(), 1);
      double p[3];
      poly->GetPoint(2, p);
      EXPECT_EQ(p[0], 2.0);
      EXPECT_EQ(p[1], double(k));
      EXPECT_EQ(poly->GetPointData()->GetArray("step")->GetComponent(0, 0), double(k));
      EXPECT_EQ(poly->GetCellData()->GetArray("line_step")->GetComponent(0, 0), 10.0 + k);
    }
  }
}
