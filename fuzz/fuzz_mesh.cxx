// libFuzzer harness for one mesh format: the input is written to a file with the format's
// extension and read with bender::ReadMesh (pre-validator, then the VTK reader or the OFF
// reader). Any outcome but a mesh or a MeshIOError with a clean one-line message is a
// finding. BENDER_FUZZ_EXTENSION is set per target (".stl", ".ply", ...).

#include "FuzzSupport.h"
#include "MeshIO.h"

#include <vtkAbstractArray.h>
#include <vtkCellData.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <cmath>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const bool quiet = []
  {
    vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
    return true;
  }();
  (void)quiet;
  const std::string path =
    bender_fuzz::WriteInput(std::string("input") + BENDER_FUZZ_EXTENSION, data, size);
  try
  {
    vtkSmartPointer<vtkPolyData> mesh = bender::ReadMesh(path);
    // ReadMesh promises finite points, cell ids in range and attribute arrays as long as the
    // points and cells.
    for (int a = 0; a < mesh->GetPointData()->GetNumberOfArrays(); ++a)
    {
      if (mesh->GetPointData()->GetAbstractArray(a)->GetNumberOfTuples() !=
        mesh->GetNumberOfPoints())
      {
        std::abort();
      }
    }
    for (int a = 0; a < mesh->GetCellData()->GetNumberOfArrays(); ++a)
    {
      if (mesh->GetCellData()->GetAbstractArray(a)->GetNumberOfTuples() != mesh->GetNumberOfCells())
      {
        std::abort();
      }
    }
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      double p[3];
      mesh->GetPoint(i, p);
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      {
        std::abort();
      }
    }
  }
  catch (const bender::MeshIOError& e)
  {
    bender_fuzz::CheckMessage(e.what());
  }
  return 0;
}
