#include "MeshIO.h"

#include "CoordinateRange.h"
#include "FileUtilities.h"
#include "InputValidation.h"
#include "MeshFormats.h"
#include "MeshUnit.h"
#include "StringUtil.h"
#include "VtkMessageGuard.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <array>
#include <cstdint>
#include <sstream>
#include <tuple>

namespace bender
{

namespace
{

using io_detail::FailMesh;

// Every point finite, every cell index in range: a reader that returns less is a bad file.
void CheckMesh(const std::string& path, vtkPolyData* mesh)
{
  if (!mesh || !mesh->GetPoints() || mesh->GetNumberOfPoints() == 0)
  {
    FailMesh(path, "no points in the file");
  }
  const vtkIdType n = mesh->GetNumberOfPoints();
  const std::string range = MeshCoordinateRangeProblem(mesh);
  if (!range.empty())
  {
    FailMesh(path, range);
  }
  const std::array<std::pair<vtkCellArray*, const char*>, 4> arrays{ {
    { mesh->GetVerts(), "vertex cell" },
    { mesh->GetLines(), "line" },
    { mesh->GetPolys(), "face" },
    { mesh->GetStrips(), "triangle strip" },
  } };
  for (const auto& [cells, what] : arrays)
  {
    if (!cells || cells->GetNumberOfConnectivityIds() == 0)
    {
      continue;
    }
    double range[2];
    cells->GetConnectivityArray()->GetRange(range, 0);
    if (range[0] < 0 || range[1] >= static_cast<double>(n))
    {
      std::ostringstream msg;
      msg << "a " << what << " refers to point " << (range[0] < 0 ? range[0] : range[1])
          << ", but the file has " << n << " points";
      FailMesh(path, msg.str());
    }
  }
  // Every point (cell) attribute array as long as the points (cells): filters copy attribute
  // tuples by point and cell id and would read past the end of a shorter one.
  const std::array<std::tuple<vtkFieldData*, vtkIdType, const char*>, 2> attributes{ {
    { mesh->GetPointData(), n, "point" },
    { mesh->GetCellData(), mesh->GetNumberOfCells(), "cell" },
  } };
  for (const auto& [data, expected, what] : attributes)
  {
    for (int a = 0; data && a < data->GetNumberOfArrays(); ++a)
    {
      vtkAbstractArray* array = data->GetAbstractArray(a);
      if (array && array->GetNumberOfTuples() != expected)
      {
        const char* name = array->GetName();
        std::ostringstream msg;
        msg << what << " data array \"" << io_detail::QuoteBytes(name ? name : "") << "\" has "
            << array->GetNumberOfTuples() << " values, but the file has " << expected << " " << what
            << "s";
        FailMesh(path, msg.str());
      }
    }
  }
}

// "unknown extension ".xyz"" or "no file extension", with the extensions that are known.
std::string UnknownExtension(const std::string& path, MeshAccess access)
{
  const std::string ext = LowerExtension(path);
  return (ext.empty() ? std::string("no file extension") : "unknown extension \"" + ext + "\"") +
    (access == MeshAccess::Read ? " (meshes are read from " : " (meshes are written as ") +
    MeshExtensionList(access) + ")";
}

vtkSmartPointer<vtkPolyData> ReadMeshUnchecked(const std::string& path)
{
  std::uintmax_t size = 0;
  std::string problem;
  if (!io_detail::CheckReadableFile(path, size, problem))
  {
    FailMesh(path, problem);
  }
  if (size > io_detail::MaxMeshFileBytes)
  {
    FailMesh(path,
      "larger than the " + std::to_string(io_detail::MaxMeshFileBytes >> 20) +
        " MiB limit for mesh files (" + std::to_string(size >> 20) + " MiB)");
  }
  const std::optional<MeshFormat> format = FindMeshFormat(path);
  if (!format || !format->CanRead())
  {
    FailMesh(path, UnknownExtension(path, MeshAccess::Read));
  }
  return format->read(path, size);
}

} // namespace

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path)
{
  StatedSpace stated;
  return ReadMesh(path, stated);
}

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path, StatedSpace& stated)
{
  vtkSmartPointer<vtkPolyData> mesh;
  try
  {
    mesh = ReadMeshUnchecked(path);
  }
  catch (const MeshIOError&)
  {
    throw;
  }
  catch (const std::bad_alloc&)
  {
    // A corrupt count in a binary header can ask a VTK reader for terabytes.
    FailMesh(path, "corrupt file (its sizes ask for more memory than there is)");
  }
  catch (const std::exception& e) // VTK's readers and the standard library on a corrupt file
  {
    FailMesh(path, std::string("corrupt file (") + e.what() + ")");
  }
  CheckMesh(path, mesh);
  stated = ToLpsMillimetres(path, mesh);
  return mesh;
}

void WriteMesh(vtkPolyData* mesh, const std::string& path, const MeshWriteOptions& options)
{
  if (!mesh || !mesh->GetPoints() || mesh->GetNumberOfPoints() == 0)
  {
    FailMesh(path, "refusing to write a mesh without points");
  }
  const std::string range = MeshCoordinateRangeProblem(mesh);
  if (!range.empty())
  {
    FailMesh(path, "refusing to write " + range);
  }
  const std::optional<MeshFormat> format = FindMeshFormat(path);
  if (!format || !format->CanWrite())
  {
    FailMesh(path, UnknownExtension(path, MeshAccess::Write));
  }
  const MeshWriter write = format->write;
  std::string problem;
  if (!AtomicWrite(
        path,
        [&](const std::string& temp, std::string& tempProblem)
        { return write(mesh, temp, options, tempProblem); },
        problem))
  {
    FailMesh(path, problem);
  }
}

} // namespace bender
