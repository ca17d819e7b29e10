#include "CfdTestUtilities.h"

#include "ApplyPlan.h"
#include "CfdVerificationTubes.h"
#include "DemoPipeline.h"
#include "MeshIO.h"
#include "PatchLabels.h"
#include "PrepareForCfd.h"
#include "WarpPlanIO.h"
#include "vtkBenderCapFilter.h"

#include <vtkFieldData.h>
#include <vtkNew.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace bender::test
{

vtkSmartPointer<vtkPolyData> CappedAneurysm(bool bent)
{
  vtkSmartPointer<vtkPolyData> surface =
    ReadMesh(std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl");
  if (bent)
  {
    const WarpPlan plan =
      ReadWarpPlan(std::string(BENDER_SOURCE_DIR) + "/data/demo/demo.bender.json");
    surface = ApplyPlan(surface, plan).output;
  }
  vtkNew<vtkBenderCapFilter> cap;
  cap->SetInputData(surface);
  cap->Update();
  if (cap->GetNumberOfCaps() != 3)
  {
    throw std::runtime_error("the aneurysm should have 3 caps, got " +
      std::to_string(cap->GetNumberOfCaps()) + " " + cap->GetLastError());
  }
  vtkSmartPointer<vtkPolyData> capped = vtkSmartPointer<vtkPolyData>::New();
  capped->DeepCopy(cap->GetOutput());
  return capped;
}

vtkSmartPointer<vtkPolyData> CappedTube(double length, double radius, int rings, int sides)
{
  // The wall of the one tube generator, capped as a vessel is (vtkBenderCapFilter).
  const vtkSmartPointer<vtkPolyData> tube =
    SweepOpenTube(StraightCentreline(0.0, length, rings - 1), radius, sides);
  vtkNew<vtkBenderCapFilter> cap;
  cap->SetInputData(tube);
  cap->Update();
  if (cap->GetNumberOfCaps() != 2)
  {
    throw std::runtime_error("the tube should have 2 caps, got " +
      std::to_string(cap->GetNumberOfCaps()) + " " + cap->GetLastError());
  }
  vtkSmartPointer<vtkPolyData> capped = vtkSmartPointer<vtkPolyData>::New();
  capped->DeepCopy(cap->GetOutput());
  // The cap filter names the ends by its own order: the end at x = 0 is the inlet.
  std::vector<PatchLabel> labels = ReadPatchLabels(capped);
  const std::vector<int> ids = CellPatchIds(capped);
  for (auto& label : labels)
  {
    if (label.type == PatchType::Wall)
    {
      continue;
    }
    for (std::size_t c = 0; c < ids.size(); ++c)
    {
      if (ids[c] == label.id)
      {
        double x[3];
        capped->GetPoint(capped->GetCell(static_cast<vtkIdType>(c))->GetPointId(0), x);
        const bool inlet = x[0] < 0.5 * length;
        label.name = inlet ? "inlet" : "outlet_1";
        label.type = inlet ? PatchType::Inlet : PatchType::Outlet;
        break;
      }
    }
  }
  WritePatchLabels(capped, ids, labels);
  return capped;
}

vtkSmartPointer<vtkPolyData> PreparedDemoVessel(bool bent)
{
  static vtkSmartPointer<vtkPolyData> prepared[2];
  auto& result = prepared[bent ? 1 : 0];
  if (result)
  {
    return result;
  }
  static vtkSmartPointer<vtkPolyData> segmented;
  if (!segmented)
  {
    // 0.8 mm voxels (the demo job uses 0.5): a quarter of the triangles, meshed in seconds.
    DemoOptions demoOptions;
    demoOptions.spacing = 0.8;
    segmented = SegmentDemoVessel(DemoVesselPath(), demoOptions).surface;
  }
  // As the demo job does: bend the segmented vessel, then make it CFD-ready (the flow
  // extensions continue the final ends; the demo plan applied after them folds the surface).
  vtkSmartPointer<vtkPolyData> surface = segmented;
  if (bent)
  {
    surface = ApplyPlan(segmented, ReadWarpPlan(DemoPlanPath())).output;
  }
  PrepareForCfdOptions options;
  options.inputName = bent ? "the bent demo vessel" : "the segmented demo vessel";
  result = PrepareForCfd(surface, options).surface;
  return result;
}

TemporaryFolder::TemporaryFolder(const std::string& tag)
{
  std::string pattern = (fs::temp_directory_path() / ("bender-" + tag + "-XXXXXX")).string();
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  if (!mkdtemp(buffer.data()))
  {
    throw std::runtime_error("cannot create a temporary folder");
  }
  this->Folder = buffer.data();
}

TemporaryFolder::~TemporaryFolder()
{
  std::error_code ec;
  if (!std::getenv("BENDER_KEEP_TEST_FILES"))
  {
    fs::remove_all(this->Folder, ec);
  }
}

std::string RunIn(const std::string& folder, const std::string& command, int& status)
{
  std::string quoted = "'";
  for (const char c : folder)
  {
    quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  quoted += "'";
  const std::string full = "cd " + quoted + " && (" + command + ") </dev/null 2>&1";
  FILE* pipe = popen(full.c_str(), "r");
  if (!pipe)
  {
    status = -1;
    return "";
  }
  std::string output;
  std::array<char, 4096> buffer;
  std::size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
  {
    output.append(buffer.data(), n);
  }
  const int raw = pclose(pipe);
  status = (raw != -1 && WIFEXITED(raw)) ? WEXITSTATUS(raw) : -1;
  return output;
}

std::string ReadText(const std::string& path)
{
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

} // namespace bender::test
