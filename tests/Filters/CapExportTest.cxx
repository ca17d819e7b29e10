// vtkBenderCapFilter and ExportStl: an open tube is capped into a closed, consistently
// oriented surface with labelled caps; every export mode reassembles into the same closed
// surface with the same volume; headers state frame and unit; writes are atomic.

#include "BenderMeshCheck.h"
#include "BenderStlExport.h"
#include "MeshIO.h"
#include "PatchLabels.h"
#include "VtkErrorWatch.h"
#include "vtkBenderCapFilter.h"

#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCleanPolyData.h>
#include <vtkCylinderSource.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTriangleFilter.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace
{
// An open tube of radius 2, length 10 along y, welded and triangulated.
vtkSmartPointer<vtkPolyData> OpenTube()
{
  vtkNew<vtkCylinderSource> cyl;
  cyl->SetRadius(2.0);
  cyl->SetHeight(10.0);
  cyl->SetResolution(40);
  cyl->CappingOff();
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(cyl->GetOutputPort());
  vtkNew<vtkTriangleFilter> tri;
  tri->SetInputConnection(clean->GetOutputPort());
  tri->Update();
  return tri->GetOutput();
}

using Triangle = std::array<std::array<float, 3>, 3>;

// Reassembles STL triangles into a mesh by welding identical coordinates.
vtkSmartPointer<vtkPolyData> Weld(const std::vector<Triangle>& tris)
{
  std::map<std::array<float, 3>, vtkIdType> index;
  vtkNew<vtkPoints> pts;
  vtkNew<vtkCellArray> polys;
  for (const Triangle& t : tris)
  {
    vtkIdType ids[3];
    for (int k = 0; k < 3; ++k)
    {
      auto it = index.find(t[k]);
      if (it == index.end())
      {
        it = index.emplace(t[k], pts->InsertNextPoint(t[k][0], t[k][1], t[k][2])).first;
      }
      ids[k] = it->second;
    }
    polys->InsertNextCell(3, ids);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(pts);
  pd->SetPolys(polys);
  return pd;
}

std::vector<Triangle> ReadBinary(const std::string& path, std::string& header)
{
  std::ifstream in(path, std::ios::binary);
  char head[80];
  in.read(head, 80);
  header.assign(head, 80);
  std::uint32_t n = 0;
  in.read(reinterpret_cast<char*>(&n), 4);
  std::vector<Triangle> tris(n);
  for (auto& t : tris)
  {
    float normal[3];
    in.read(reinterpret_cast<char*>(normal), 12);
    in.read(reinterpret_cast<char*>(t.data()), 36);
    char attr[2];
    in.read(attr, 2);
  }
  EXPECT_TRUE(in.good());
  return tris;
}

// Parses an ASCII STL into solids: name -> triangles.
std::map<std::string, std::vector<Triangle>> ReadSolids(const std::string& path, std::string& text)
{
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  text = ss.str();
  std::map<std::string, std::vector<Triangle>> solids;
  std::istringstream lines(text);
  std::string line, current;
  Triangle t;
  int k = 0;
  while (std::getline(lines, line))
  {
    std::istringstream words(line);
    std::string w;
    words >> w;
    if (w == "solid")
    {
      words >> current;
    }
    else if (w == "vertex")
    {
      words >> t[k][0] >> t[k][1] >> t[k][2];
      if (++k == 3)
      {
        solids[current].push_back(t);
        k = 0;
      }
    }
  }
  return solids;
}

std::string TempDir()
{
  char tmpl[] = "/tmp/bender-export-XXXXXX";
  return mkdtemp(tmpl);
}

class CapExport : public ::testing::Test
{
protected:
  void SetUp() override { vtkOutputWindow::GetInstance()->SetDisplayModeToNever(); }
};
} // namespace

TEST_F(CapExport, OpenTubeGetsTwoLabelledCaps)
{
  auto tube = OpenTube();
  const auto open = bender::CheckMesh(tube);
  ASSERT_EQ(open.boundaryLoops.size(), 2u);
  ASSERT_EQ(open.inconsistentEdges, 0);
  vtkNew<vtkBenderCapFilter> cap;
  bendertest::VtkErrorWatch errors(cap);
  cap->SetInputData(tube);
  cap->Update();
  EXPECT_TRUE(errors.ExpectNone());
  EXPECT_EQ(cap->GetNumberOfCaps(), 2);
  EXPECT_EQ(cap->GetNumberOfSkippedLoops(), 0);
  vtkPolyData* closed = cap->GetOutput();
  const auto r = bender::CheckMesh(closed);
  EXPECT_TRUE(r.closed) << bender::FormatReportText(r, "capped");
  EXPECT_TRUE(r.Clean()) << bender::FormatReportText(r, "capped");
  EXPECT_EQ(r.inconsistentEdges, 0);
  // Volume of the inscribed prism of 40 sides, outwards (positive).
  const double exact = 0.5 * 40 * 4.0 * std::sin(2 * M_PI / 40) * 10.0;
  EXPECT_NEAR(r.volume, exact, 1e-6 * exact); // float points
  const std::vector<int> ids = bender::CellPatchIds(closed);
  std::map<int, int> perPatch;
  for (int id : ids)
  {
    ++perPatch[id];
  }
  EXPECT_EQ(perPatch.size(), 3u);
  EXPECT_EQ(perPatch[1], tube->GetNumberOfPolys());
  EXPECT_GT(perPatch[2], 40); // interior points: more triangles than a fan
  EXPECT_GT(perPatch[3], 40);
  const auto labels = bender::ReadPatchLabels(closed);
  ASSERT_EQ(labels.size(), 3u);
  EXPECT_EQ(labels[0].name, "wall");
  EXPECT_EQ(labels[1].name, "inlet");
  EXPECT_EQ(labels[1].type, bender::PatchType::Inlet);
  EXPECT_EQ(labels[2].name, "outlet_1");
  EXPECT_EQ(labels[2].type, bender::PatchType::Outlet);
}

TEST_F(CapExport, NonPlanarLoopIsLeftOpen)
{
  auto tube = OpenTube();
  // Warp one end's rim into a saddle.
  for (vtkIdType i = 0; i < tube->GetNumberOfPoints(); ++i)
  {
    double p[3];
    tube->GetPoint(i, p);
    if (p[1] > 4.9)
    {
      p[1] += 1.5 * p[0] * p[2]; // a saddle: not planar
      tube->GetPoints()->SetPoint(i, p);
    }
  }
  vtkNew<vtkBenderCapFilter> cap;
  bendertest::VtkErrorWatch errors(cap);
  cap->SetInputData(tube);
  cap->Update();
  EXPECT_TRUE(errors.ExpectNone()); // a skipped loop is counted, not an error
  EXPECT_EQ(cap->GetNumberOfCaps(), 1);
  EXPECT_EQ(cap->GetNumberOfSkippedLoops(), 1);
}

TEST_F(CapExport, EveryModeReassemblesIntoTheSameClosedSurface)
{
  vtkNew<vtkBenderCapFilter> cap;
  cap->SetInputData(OpenTube());
  cap->Update();
  vtkPolyData* closed = cap->GetOutput();
  const double volume = std::abs(bender::CheckMesh(closed).volume);
  const std::string dir = TempDir();

  // Single binary STL.
  bender::StlExportOptions options;
  auto files = bender::ExportStl(closed, dir + "/whole.stl", options);
  ASSERT_EQ(files.size(), 1u);
  std::string header;
  auto whole = bender::CheckMesh(Weld(ReadBinary(files[0], header)));
  EXPECT_EQ(header.rfind("bender export: frame LPS, unit mm", 0), 0u) << header;
  EXPECT_TRUE(whole.closed);
  EXPECT_EQ(whole.inconsistentEdges, 0);
  EXPECT_NEAR(whole.volume, volume, 1e-5 * volume);

  // Multi-solid ASCII STL, in RAS: same volume (a rotation), same orientation.
  options.patches = bender::StlPatchMode::Solids;
  options.frame = bender::StlFrame::RAS;
  files = bender::ExportStl(closed, dir + "/solids.stl", options);
  std::string text;
  const auto solids = ReadSolids(files[0], text);
  EXPECT_NE(text.find("frame RAS, unit mm"), std::string::npos);
  ASSERT_EQ(solids.size(), 3u);
  EXPECT_EQ(solids.count("wall"), 1u);
  std::vector<Triangle> all;
  for (const auto& [name, tris] : solids)
  {
    all.insert(all.end(), tris.begin(), tris.end());
  }
  auto reassembled = bender::CheckMesh(Weld(all));
  EXPECT_TRUE(reassembled.closed);
  EXPECT_EQ(reassembled.inconsistentEdges, 0);
  EXPECT_NEAR(reassembled.volume, volume, 1e-5 * volume);
  EXPECT_LT(Weld(solids.at("wall")).Get()->GetBounds()[0], 0.0); // x negated, still spans 0

  // One binary file per patch.
  options.patches = bender::StlPatchMode::Files;
  options.frame = bender::StlFrame::LPS;
  files = bender::ExportStl(closed, dir + "/patch.stl", options);
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0], dir + "/patch_wall.stl");
  all.clear();
  for (const auto& f : files)
  {
    auto tris = ReadBinary(f, header);
    EXPECT_NE(header.find("unit mm"), std::string::npos);
    all.insert(all.end(), tris.begin(), tris.end());
  }
  reassembled = bender::CheckMesh(Weld(all));
  EXPECT_TRUE(reassembled.closed);
  EXPECT_NEAR(reassembled.volume, volume, 1e-5 * volume);
  for (const auto& f : files)
  {
    std::remove(f.c_str());
  }
  std::remove((dir + "/whole.stl").c_str());
  std::remove((dir + "/solids.stl").c_str());
  rmdir(dir.c_str());
}

TEST_F(CapExport, ErrorsLeaveNothingBehind)
{
  vtkNew<vtkPolyData> empty;
  const std::string dir = TempDir();
  EXPECT_THROW(bender::ExportStl(empty, dir + "/e.stl", {}), bender::StlExportError);
  auto tube = OpenTube();
  tube->GetPoints()->SetPoint(0, std::nan(""), 0, 0);
  try
  {
    bender::ExportStl(tube, dir + "/nan.stl", {});
    ADD_FAILURE() << "no exception";
  }
  catch (const bender::StlExportError& e)
  {
    EXPECT_NE(std::string(e.what()).find("nan.stl: "), std::string::npos) << e.what();
  }
  EXPECT_THROW(
    bender::ExportStl(OpenTube(), "/nonexistent-folder/x.stl", {}), bender::StlExportError);
  EXPECT_EQ(rmdir(dir.c_str()), 0); // empty: no temporary or partial file left
  vtkNew<vtkBenderCapFilter> cap;
  bendertest::VtkErrorWatch errors(cap);
  cap->SetInputData(tube);
  cap->Update();
  EXPECT_NE(cap->GetLastError().find("non-finite"), std::string::npos);
  EXPECT_TRUE(errors.ExpectError("non-finite"));
}

// One STL per patch is all-or-nothing: when one patch file cannot be written (a folder is in
// its place), the other patch files keep their previous content or are not created.
TEST_F(CapExport, PatchFilesAreWrittenAllOrNothing)
{
  vtkNew<vtkBenderCapFilter> cap;
  cap->SetInputData(OpenTube());
  cap->Update();
  ASSERT_EQ(cap->GetNumberOfCaps(), 2);
  const std::string dir = TempDir();
  bender::StlExportOptions options;
  options.patches = bender::StlPatchMode::Files;
  const std::vector<std::string> planned = bender::PlannedStlPaths(
    bender::ReadLabelledSurface(cap->GetOutput()), dir + "/case.stl", options);
  ASSERT_EQ(planned.size(), 3u); // wall, cap_1, cap_2
  {
    std::ofstream(planned[0]) << "previous wall";
  }
  ASSERT_EQ(mkdir(planned[2].c_str(), 0755), 0);
  try
  {
    bender::ExportStl(cap->GetOutput(), dir + "/case.stl", options);
    ADD_FAILURE() << "no exception";
  }
  catch (const bender::StlExportError& e)
  {
    EXPECT_EQ(std::string(e.what()).rfind(planned[2].substr(dir.size() + 1) + ": ", 0), 0u)
      << e.what();
  }
  std::ifstream wall(planned[0]);
  const std::string previous(
    (std::istreambuf_iterator<char>(wall)), std::istreambuf_iterator<char>());
  EXPECT_EQ(previous, "previous wall");
  EXPECT_NE(access(planned[1].c_str(), F_OK), 0) << "one cap written without the other";

  // With the folder gone, all three are written.
  ASSERT_EQ(rmdir(planned[2].c_str()), 0);
  EXPECT_EQ(bender::ExportStl(cap->GetOutput(), dir + "/case.stl", options), planned);
  for (const std::string& file : planned)
  {
    EXPECT_EQ(access(file.c_str(), R_OK), 0) << file;
    std::remove(file.c_str());
  }
  EXPECT_EQ(rmdir(dir.c_str()), 0); // no temporary or kept previous file left behind
}

// The plain STL writer (for MeshIO): binary and ASCII read back as the same triangles; a
// binary header that starts with "solid" is prefixed so that readers do not take it for ASCII.
TEST_F(CapExport, PlainStlFilesReadBack)
{
  auto tube = OpenTube();
  const std::string dir = TempDir();
  std::string problem;
  ASSERT_TRUE(
    bender::WriteStlFile(tube, dir + "/b.stl", true, "solid trouble\nsecond line", problem))
    << problem;
  ASSERT_TRUE(bender::WriteStlFile(tube, dir + "/a.stl", false, "tube", problem)) << problem;
  std::ifstream binary(dir + "/b.stl", std::ios::binary);
  char head[16] = {};
  binary.read(head, 15);
  EXPECT_EQ(std::string(head), "# solid trouble");
  std::ifstream ascii(dir + "/a.stl");
  std::string first;
  std::getline(ascii, first);
  EXPECT_EQ(first, "solid tube");
  const auto triangles = static_cast<vtkIdType>(bender::CollectTriangles(tube).size() / 3);
  for (const char* name : { "/b.stl", "/a.stl" })
  {
    const auto back = bender::ReadMesh(dir + name);
    EXPECT_EQ(back->GetNumberOfPolys(), triangles) << name;
    EXPECT_EQ(back->GetNumberOfPoints(), tube->GetNumberOfPoints()) << name; // welded again
    std::remove((dir + name).c_str());
  }
  tube->GetPoints()->SetPoint(0, std::nan(""), 0, 0);
  EXPECT_FALSE(bender::WriteStlFile(tube, dir + "/n.stl", true, "", problem));
  EXPECT_NE(problem.find("non-finite"), std::string::npos) << problem;
  vtkNew<vtkPolyData> empty;
  EXPECT_FALSE(bender::WriteStlFile(empty, dir + "/e.stl", true, "", problem));
  EXPECT_EQ(problem, "the mesh has no triangles");
  std::remove((dir + "/n.stl").c_str());
  std::remove((dir + "/e.stl").c_str());
  EXPECT_EQ(rmdir(dir.c_str()), 0);
}
