// Exports for CFD meshers (issue 11): named STL solids, metres, per-patch files sharing their
// rims, TetGen .smesh/.poly with the labels as facet markers, and the patches sidecar, on a
// closed labelled cylinder whose every value is known.

#include "BenderStlExport.h"
#include "IOTestUtilities.h"
#include "InsidePoint.h"
#include "MesherTestUtilities.h"
#include "PatchLabels.h"
#include "PatchSidecar.h"
#include "TetgenExport.h"

#include <nlohmann/json.hpp>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSelectEnclosedPoints.h>
#include <vtkSmartPointer.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <sstream>

namespace
{
using bender_test::LabelledCylinder;
using bender_test::Offset;
using bender_test::ReadText;
using bender_test::Rings;
using bender_test::Segments;
using bender_test::TempDir;

constexpr std::size_t WallTriangles = 2 * Segments * (Rings - 1);

using Vertex = std::array<float, 3>;
struct Solid
{
  std::string name;
  std::vector<Vertex> vertices; // three per facet
};

std::vector<Solid> ReadAsciiSolids(const std::string& path)
{
  std::istringstream in(ReadText(path));
  std::vector<Solid> solids;
  std::string line;
  while (std::getline(in, line))
  {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "solid")
    {
      solids.emplace_back();
      words >> solids.back().name;
    }
    else if (word == "vertex")
    {
      Vertex v;
      words >> v[0] >> v[1] >> v[2];
      solids.back().vertices.push_back(v);
    }
  }
  return solids;
}

std::vector<Vertex> ReadBinaryVertices(const std::string& path, std::string& header)
{
  const std::string bytes = ReadText(path);
  std::vector<Vertex> out;
  if (bytes.size() < 84)
  {
    return out;
  }
  header = bytes.substr(0, 80);
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  EXPECT_EQ(bytes.size(), 84u + 50u * count) << path;
  for (std::uint32_t f = 0; f < count && 84 + 50 * (f + 1) <= bytes.size(); ++f)
  {
    for (int k = 0; k < 3; ++k)
    {
      Vertex v;
      std::memcpy(v.data(), bytes.data() + 84 + 50 * f + 12 * (k + 1), 12);
      out.push_back(v);
    }
  }
  return out;
}

std::set<std::array<std::uint32_t, 3>> Bits(const std::vector<Vertex>& vertices)
{
  std::set<std::array<std::uint32_t, 3>> out;
  for (const Vertex& v : vertices)
  {
    std::array<std::uint32_t, 3> b;
    std::memcpy(b.data(), v.data(), 12);
    out.insert(b);
  }
  return out;
}

// Whether the points are inside the surface by VTK's own test (independent of the winding
// number the sidecar uses).
bool InsideByVtk(vtkPolyData* surface, const double p[3])
{
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(p);
  vtkNew<vtkPolyData> probe;
  probe->SetPoints(pts);
  vtkNew<vtkSelectEnclosedPoints> select;
  select->SetInputData(probe);
  select->SetSurfaceData(surface);
  select->SetCheckSurface(true);
  select->Update();
  return select->IsInside(0) != 0;
}

// The surface transformed into the written coordinates (to check the sidecar against).
vtkSmartPointer<vtkPolyData> Transformed(vtkPolyData* mesh, const bender::ExportTransform& t)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(mesh);
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    out->GetPoint(i, p);
    t.Apply(p, q);
    out->GetPoints()->SetPoint(i, q);
  }
  return out;
}
} // namespace

TEST(MesherExport, SolidsAreNamedByPatchWithTheirTriangles)
{
  TempDir dir;
  bender::StlExportOptions options;
  options.patches = bender::StlPatchMode::Solids;
  const auto written = bender::ExportStl(LabelledCylinder(), dir / "v.stl", options);
  ASSERT_EQ(written.size(), 1u);
  const auto solids = ReadAsciiSolids(written[0]);
  ASSERT_EQ(solids.size(), 3u);
  EXPECT_EQ(solids[0].name, "wall");
  EXPECT_EQ(solids[1].name, "inlet");
  EXPECT_EQ(solids[2].name, "outlet_1");
  EXPECT_EQ(solids[0].vertices.size(), 3 * WallTriangles);
  EXPECT_EQ(solids[1].vertices.size(), 3u * Segments);
  EXPECT_EQ(solids[2].vertices.size(), 3u * Segments);
  const std::string text = ReadText(written[0]);
  EXPECT_NE(text.find("endsolid wall  bender export: frame LPS, unit mm"), std::string::npos);
  EXPECT_EQ(bender::PatchNames(bender::ReadLabelledSurface(LabelledCylinder())),
    (std::vector<std::string>{ "wall", "inlet", "outlet_1" }));
}

TEST(MesherExport, MetresAreMillimetresOverAThousand)
{
  TempDir dir;
  const auto mesh = LabelledCylinder();
  bender::StlExportOptions options;
  bender::ExportStl(mesh, dir / "mm.stl", options);
  options.unit = "m";
  bender::ExportStl(mesh, dir / "m.stl", options);
  std::string mmHeader, mHeader;
  const auto mm = ReadBinaryVertices(dir / "mm.stl", mmHeader);
  const auto m = ReadBinaryVertices(dir / "m.stl", mHeader);
  EXPECT_EQ(mmHeader.rfind("bender export: frame LPS, unit mm", 0), 0u) << mmHeader;
  EXPECT_EQ(mHeader.rfind("bender export: frame LPS, unit m ", 0), 0u) << mHeader;
  ASSERT_EQ(mm.size(), m.size());
  ASSERT_FALSE(m.empty());
  double maxX = 0;
  for (std::size_t k = 0; k < m.size(); ++k)
  {
    for (int a = 0; a < 3; ++a)
    {
      const double expected = static_cast<double>(mm[k][a]) / 1000.0;
      EXPECT_NEAR(m[k][a], expected, 1e-6 * std::abs(expected) + 1e-12) << k;
    }
    maxX = std::max(maxX, static_cast<double>(m[k][0]));
  }
  EXPECT_NEAR(maxX, (Offset + 1) / 1000.0, 1e-7); // 0.101 m, not 101
  // Sizes: the 10 mm cylinder is 0.01 m long.
  double maxZ = 0;
  for (const Vertex& v : m)
  {
    maxZ = std::max(maxZ, static_cast<double>(v[2]));
  }
  EXPECT_NEAR(maxZ, 0.01, 1e-9);
  options.unit = "cm";
  EXPECT_THROW(bender::ExportStl(mesh, dir / "cm.stl", options), bender::StlExportError);
  EXPECT_FALSE(std::filesystem::exists(dir / "cm.stl"));
}

TEST(MesherExport, PerPatchFilesShareTheirRimVerticesBitForBit)
{
  TempDir dir;
  bender::StlExportOptions options;
  options.patches = bender::StlPatchMode::Files;
  options.unit = "m";
  options.frame = bender::StlFrame::RAS;
  const auto written = bender::ExportStl(LabelledCylinder(), dir / "v.stl", options);
  ASSERT_EQ(written,
    (std::vector<std::string>{ dir / "v_wall.stl", dir / "v_inlet.stl", dir / "v_outlet_1.stl" }));
  EXPECT_EQ(bender::PlannedStlPaths(
              bender::ReadLabelledSurface(LabelledCylinder()), dir / "v.stl", options),
    written);
  std::string header;
  const auto wall = Bits(ReadBinaryVertices(written[0], header));
  EXPECT_NE(header.find("frame RAS, unit m, patch wall"), std::string::npos) << header;
  for (std::size_t k = 1; k < 3; ++k)
  {
    const auto cap = Bits(ReadBinaryVertices(written[k], header));
    EXPECT_EQ(cap.size(), Segments + 1u) << written[k]; // the rim and the fan's centre
    std::size_t shared = 0;
    for (const auto& v : cap)
    {
      shared += wall.count(v);
    }
    EXPECT_EQ(shared, static_cast<std::size_t>(Segments)) << written[k];
  }
}

TEST(MesherExport, LegacyPatchIdSurfacesKeepWorking)
{
  auto mesh = LabelledCylinder();
  const std::vector<int> ids = bender::CellPatchIds(mesh);
  vtkNew<vtkIntArray> legacy;
  legacy->SetName(bender::kLegacyPatchIdArrayName);
  for (int id : ids)
  {
    legacy->InsertNextValue(id - 1);
  }
  auto old = vtkSmartPointer<vtkPolyData>::New();
  old->SetPoints(mesh->GetPoints());
  old->SetPolys(mesh->GetPolys());
  old->GetCellData()->AddArray(legacy);
  EXPECT_EQ(bender::PatchNames(bender::ReadLabelledSurface(old)),
    (std::vector<std::string>{ "wall", "cap_1", "cap_2" }));
  TempDir dir;
  bender::StlExportOptions options;
  options.patches = bender::StlPatchMode::Solids;
  const auto solids = ReadAsciiSolids(bender::ExportStl(old, dir / "old.stl", options)[0]);
  ASSERT_EQ(solids.size(), 3u);
  EXPECT_EQ(solids[1].name, "cap_1");
  EXPECT_EQ(solids[1].vertices.size(), 3u * Segments);
}

TEST(MesherExport, BadLabelsAndGeometryAreRefusedNamingTheProblem)
{
  TempDir dir;
  bender::StlExportOptions options;
  options.patches = bender::StlPatchMode::Solids;
  auto mesh = LabelledCylinder();
  mesh->GetCellData()->GetArray(bender::kCellEntityIdsArrayName)->SetTuple1(5, 0);
  try
  {
    bender::ExportStl(mesh, dir / "bad.stl", options);
    ADD_FAILURE() << "a label 0 was exported";
  }
  catch (const bender::StlExportError& e)
  {
    EXPECT_NE(
      std::string(e.what()).find("bad.stl: the cell array CellEntityIds"), std::string::npos)
      << e.what();
  }
  // The table of a sound cylinder with the bad cell array: the cells are checked when collected.
  const bender::LabelledSurface badCells{ mesh, bender::ReadPatchLabels(LabelledCylinder()) };
  EXPECT_THROW(bender::TetgenText(badCells,
                 bender::TetgenFormat::Smesh,
                 bender::ExportTransform(bender::StlFrame::LPS, "mm"),
                 nullptr),
    bender::StlExportError);
  auto nan = LabelledCylinder();
  nan->GetPoints()->SetPoint(3, std::nan(""), 0, 0);
  EXPECT_THROW(bender::ComputePatchSidecar(bender::ReadLabelledSurface(nan),
                 bender::ExportTransform(bender::StlFrame::LPS, "mm")),
    bender::StlExportError);
  vtkNew<vtkPolyData> empty;
  EXPECT_THROW(bender::ExportStl(empty, dir / "e.stl", options), bender::StlExportError);
  EXPECT_THROW(bender::ExportTransform(bender::StlFrame::LPS, "inch"), bender::StlExportError);
  EXPECT_TRUE(dir.Entries().empty());
}

namespace
{
struct ParsedTetgen
{
  std::vector<std::array<double, 3>> nodes;
  std::vector<std::array<long long, 3>> facets;
  std::vector<int> markers;
  std::vector<std::array<double, 3>> regions;
};

// A reader of the subset of .smesh / .poly that TetgenText writes, strict about counts.
ParsedTetgen ParseTetgen(const std::string& text, bool poly)
{
  std::istringstream lines(text);
  std::vector<std::string> data;
  std::string line;
  while (std::getline(lines, line))
  {
    const auto hash = line.find('#');
    line = line.substr(0, hash);
    if (line.find_first_not_of(" \t\r") != std::string::npos)
    {
      data.push_back(line);
    }
  }
  ParsedTetgen out;
  std::size_t at = 0;
  auto next = [&]() -> std::istringstream
  {
    EXPECT_LT(at, data.size());
    return std::istringstream(at < data.size() ? data[at++] : std::string());
  };
  long long nodes = 0, dim = 0, attributes = 0, boundary = 0;
  next() >> nodes >> dim >> attributes >> boundary;
  EXPECT_EQ(dim, 3);
  for (long long k = 0; k < nodes; ++k)
  {
    long long index = 0;
    std::array<double, 3> p;
    next() >> index >> p[0] >> p[1] >> p[2];
    EXPECT_EQ(index, k + 1);
    out.nodes.push_back(p);
  }
  long long facets = 0, markers = 0;
  next() >> facets >> markers;
  EXPECT_EQ(markers, 1);
  for (long long f = 0; f < facets; ++f)
  {
    int corners = 0, marker = 0;
    std::array<long long, 3> c{};
    if (poly)
    {
      int polygons = 0, holes = -1;
      next() >> polygons >> holes >> marker;
      EXPECT_EQ(polygons, 1);
      EXPECT_EQ(holes, 0);
      next() >> corners >> c[0] >> c[1] >> c[2];
    }
    else
    {
      next() >> corners >> c[0] >> c[1] >> c[2] >> marker;
    }
    EXPECT_EQ(corners, 3);
    for (long long v : c)
    {
      EXPECT_GE(v, 1);
      EXPECT_LE(v, nodes);
    }
    out.facets.push_back(c);
    out.markers.push_back(marker);
  }
  long long holes = -1;
  next() >> holes;
  EXPECT_EQ(holes, 0);
  long long regions = -1;
  next() >> regions;
  for (long long r = 0; r < regions; ++r)
  {
    long long index = 0;
    std::array<double, 3> p;
    int attribute = 0;
    next() >> index >> p[0] >> p[1] >> p[2] >> attribute;
    EXPECT_EQ(attribute, 1);
    out.regions.push_back(p);
  }
  EXPECT_EQ(at, data.size()) << "trailing lines";
  return out;
}
} // namespace

TEST(MesherExport, SmeshAndPolyParseBackWithEveryMarker)
{
  const auto mesh = LabelledCylinder();
  const bender::LabelledSurface labelled = bender::ReadLabelledSurface(mesh);
  const bender::ExportTransform metres(bender::StlFrame::LPS, "m");
  const auto sidecar = bender::ComputePatchSidecar(labelled, metres);
  ASSERT_TRUE(sidecar.hasInsidePoint);
  for (bool poly : { false, true })
  {
    const std::string text = bender::TetgenText(labelled,
      poly ? bender::TetgenFormat::Poly : bender::TetgenFormat::Smesh,
      metres,
      sidecar.insidePoint.data());
    EXPECT_NE(text.find("unit m"), std::string::npos);
    EXPECT_NE(text.find("1=wall 2=inlet 3=outlet_1"), std::string::npos);
    const ParsedTetgen parsed = ParseTetgen(text, poly);
    EXPECT_EQ(parsed.nodes.size(), static_cast<std::size_t>(mesh->GetNumberOfPoints()));
    ASSERT_EQ(parsed.facets.size(), static_cast<std::size_t>(mesh->GetNumberOfCells()));
    std::map<int, std::size_t> perMarker;
    for (int m : parsed.markers)
    {
      ++perMarker[m];
    }
    EXPECT_EQ(perMarker,
      (std::map<int, std::size_t>{ { 1, WallTriangles },
        { 2, static_cast<std::size_t>(Segments) },
        { 3, static_cast<std::size_t>(Segments) } }));
    // Coordinates in metres, read back to the last bit (17 digits).
    double p[3], q[3];
    mesh->GetPoint(mesh->GetPolys()->GetData()->GetValue(1), p);
    metres.Apply(p, q);
    EXPECT_EQ(parsed.nodes[0][0], q[0]);
    EXPECT_EQ(parsed.nodes[0][2], q[2]);
    ASSERT_EQ(parsed.regions.size(), 1u);
    EXPECT_TRUE(InsideByVtk(Transformed(mesh, metres), parsed.regions[0].data()));
  }
  bender::TetgenFormat format;
  EXPECT_TRUE(bender::TetgenFormatForPath("/a/b.SMESH", format));
  EXPECT_EQ(format, bender::TetgenFormat::Smesh);
  EXPECT_TRUE(bender::TetgenFormatForPath("b.poly", format));
  EXPECT_EQ(format, bender::TetgenFormat::Poly);
  EXPECT_FALSE(bender::TetgenFormatForPath("b.stl", format));
}

TEST(MesherExport, SidecarMeasuresEachPatch)
{
  for (bool flip : { false, true })
  {
    const auto mesh = LabelledCylinder(flip);
    const bender::ExportTransform mm(bender::StlFrame::LPS, "mm");
    const auto sidecar = bender::ComputePatchSidecar(bender::ReadLabelledSurface(mesh), mm);
    EXPECT_TRUE(sidecar.closed);
    ASSERT_EQ(sidecar.patches.size(), 3u);
    const auto& wall = sidecar.patches[0];
    const auto& inlet = sidecar.patches[1];
    const auto& outlet = sidecar.patches[2];
    EXPECT_EQ(wall.label.name, "wall");
    EXPECT_FALSE(wall.hasNormal);
    EXPECT_EQ(inlet.label.type, bender::PatchType::Inlet);
    EXPECT_EQ(outlet.label.name, "outlet_1");
    // Unit discs (inscribed 128-gons): area pi to 1 %, diameter 2.
    EXPECT_NEAR(inlet.area, M_PI, 0.01 * M_PI);
    EXPECT_NEAR(outlet.area, M_PI, 0.01 * M_PI);
    EXPECT_NEAR(inlet.equivalentDiameter, 2.0, 0.01);
    EXPECT_NEAR(wall.area, 2 * M_PI * 10, 0.01 * 2 * M_PI * 10);
    // Outward normals whatever the order of the triangles' corners.
    ASSERT_TRUE(inlet.hasNormal);
    ASSERT_TRUE(outlet.hasNormal);
    EXPECT_NEAR(inlet.normal[2], -1.0, 1e-9) << "flip " << flip;
    EXPECT_NEAR(outlet.normal[2], 1.0, 1e-9) << "flip " << flip;
    EXPECT_NEAR(inlet.centre[0], Offset, 1e-9);
    EXPECT_NEAR(inlet.centre[2], 0.0, 1e-9);
    EXPECT_NEAR(outlet.centre[2], 10.0, 1e-9);
    EXPECT_NEAR(sidecar.volume, 10 * inlet.area, 1e-6);
    ASSERT_TRUE(sidecar.hasInsidePoint);
    EXPECT_TRUE(InsideByVtk(mesh, sidecar.insidePoint.data()));
    // Far from the wall: about the middle of the lumen (radius 1).
    EXPECT_GT(sidecar.insideClearance, 0.5);
  }
  // In RAS metres the same values, transformed.
  const auto mesh = LabelledCylinder();
  const bender::ExportTransform ras(bender::StlFrame::RAS, "m");
  const auto sidecar = bender::ComputePatchSidecar(bender::ReadLabelledSurface(mesh), ras);
  EXPECT_NEAR(sidecar.patches[1].area, M_PI * 1e-6, 0.01 * M_PI * 1e-6);
  EXPECT_NEAR(sidecar.patches[1].centre[0], -Offset / 1000, 1e-12);
  EXPECT_NEAR(sidecar.patches[2].normal[2], 1.0, 1e-9);
  ASSERT_TRUE(sidecar.hasInsidePoint);
  EXPECT_TRUE(InsideByVtk(Transformed(mesh, ras), sidecar.insidePoint.data()));
  const auto json = nlohmann::json::parse(bender::PatchSidecarJson(sidecar));
  EXPECT_EQ(json.at("unit"), "m");
  EXPECT_EQ(json.at("frame"), "RAS");
  EXPECT_EQ(json.at("patches").size(), 3u);
  EXPECT_EQ(json.at("patches")[1].at("name"), "inlet");
  EXPECT_EQ(json.at("patches")[1].at("type"), "inlet");
  EXPECT_EQ(json.at("patches")[1].at("id"), 2);
  EXPECT_TRUE(json.at("patches")[0].at("normal").is_null());
  EXPECT_EQ(json.at("insidePoint").size(), 3u);
  EXPECT_EQ(bender::PatchSidecarPath("/d/vessel.stl"), "/d/vessel.patches.json");
  EXPECT_EQ(bender::PatchSidecarPath("/d.x/vessel"), "/d.x/vessel.patches.json");
}

TEST(MesherExport, AnOpenSurfaceHasNoInsidePoint)
{
  auto mesh = LabelledCylinder();
  // Drop the outlet fan: the surface is open there.
  auto open = vtkSmartPointer<vtkPolyData>::New();
  open->SetPoints(mesh->GetPoints());
  vtkNew<vtkCellArray> polys;
  const std::vector<int> ids = bender::CellPatchIds(mesh);
  std::vector<int> kept;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    if (ids[static_cast<std::size_t>(c)] != 3)
    {
      vtkIdType n;
      const vtkIdType* pts;
      mesh->GetCellPoints(c, n, pts);
      polys->InsertNextCell(n, pts);
      kept.push_back(ids[static_cast<std::size_t>(c)]);
    }
  }
  open->SetPolys(polys);
  bender::WritePatchLabels(open,
    kept,
    { { 1, "wall", bender::PatchType::Wall }, { 2, "inlet", bender::PatchType::Inlet } });
  const auto sidecar = bender::ComputePatchSidecar(
    bender::ReadLabelledSurface(open), bender::ExportTransform(bender::StlFrame::LPS, "mm"));
  EXPECT_FALSE(sidecar.closed);
  EXPECT_FALSE(sidecar.hasInsidePoint);
  EXPECT_TRUE(nlohmann::json::parse(bender::PatchSidecarJson(sidecar)).at("insidePoint").is_null());
}

TEST(MesherExport, WindingNumberTellsInsideFromOutside)
{
  const auto mesh = LabelledCylinder();
  std::vector<std::array<double, 3>> points(static_cast<std::size_t>(mesh->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    mesh->GetPoint(i, points[static_cast<std::size_t>(i)].data());
  }
  std::vector<std::array<vtkIdType, 3>> tris;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    vtkIdType n;
    const vtkIdType* pts;
    mesh->GetCellPoints(c, n, pts);
    tris.push_back({ pts[0], pts[1], pts[2] });
  }
  const double inside[3] = { Offset + 0.9, 0, 5 };
  const double outside[3] = { Offset + 1.1, 0, 5 };
  const double beyond[3] = { Offset, 0, 10.5 };
  EXPECT_NEAR(bender::WindingNumber(points, tris, inside), 1.0, 1e-6);
  EXPECT_NEAR(bender::WindingNumber(points, tris, outside), 0.0, 1e-6);
  EXPECT_NEAR(bender::WindingNumber(points, tris, beyond), 0.0, 1e-6);
}
