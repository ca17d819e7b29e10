#include "MeshWriters.h"

#include "OffFormat.h"
#include "StringUtil.h"
#include "TetgenExport.h"
#include "VtkMessageGuard.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkNew.h>
#include <vtkOBJWriter.h>
#include <vtkPLYWriter.h>
#include <vtkPolyData.h>
#include <vtkPolyDataWriter.h>
#include <vtkSTLWriter.h>
#include <vtkTriangleFilter.h>
#include <vtkXMLPolyDataWriter.h>

#include <fstream>
#include <iterator>

namespace bender
{
namespace io_detail
{

namespace
{

// Polygons and strips as triangles, for the formats that hold only triangles.
vtkSmartPointer<vtkPolyData> Triangulated(vtkPolyData* mesh)
{
  bool onlyTriangles = mesh->GetNumberOfStrips() == 0;
  if (onlyTriangles && mesh->GetPolys())
  {
    auto it = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal() && onlyTriangles; it->GoToNextCell())
    {
      vtkIdType npts;
      const vtkIdType* ids;
      it->GetCurrentCell(npts, ids);
      onlyTriangles = npts == 3;
    }
  }
  if (onlyTriangles)
  {
    return mesh;
  }
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(mesh);
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  triangles->Update();
  vtkSmartPointer<vtkPolyData> result = triangles->GetOutput();
  return result;
}

bool WriteTetgenMesh(vtkPolyData* mesh,
  const std::string& file,
  TetgenFormat format,
  std::string& problem)
{
  try
  {
    return TetgenFile(mesh, file, format, ExportTransform(StlFrame::LPS, "mm"), nullptr)
      .produce(file, problem);
  }
  catch (const StlExportError& e)
  {
    problem = e.what();
    return false;
  }
}

} // namespace

bool WriteStlMesh(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions& options,
  std::string& problem)
{
  vtkSmartPointer<vtkPolyData> triangles = Triangulated(mesh);
  if (triangles->GetNumberOfPolys() == 0)
  {
    problem = "STL holds triangles only, and the mesh has none";
    return false;
  }
  vtkNew<vtkSTLWriter> writer;
  writer->SetInputData(triangles);
  writer->SetFileName(file.c_str());
  if (options.stlEncoding == StlEncoding::Binary)
  {
    writer->SetFileTypeToBinary();
    std::string header = OneLine(options.header, 80);
    // A binary header that starts with "solid" makes other readers take it for ASCII.
    if (ToLower(header.substr(0, 5)) == "solid")
    {
      header = OneLine("# " + header, 80);
    }
    if (!options.header.empty())
    {
      writer->SetHeader(header.c_str());
    }
  }
  else
  {
    writer->SetFileTypeToASCII();
    if (!options.header.empty())
    {
      writer->SetHeader(OneLine(options.header, 200).c_str());
    }
  }
  return RunWriter(writer.Get(), problem);
}

bool WriteObjMesh(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions& options,
  std::string& problem)
{
  vtkNew<vtkOBJWriter> writer;
  writer->SetInputData(mesh);
  writer->SetFileName(file.c_str());
  if (!RunWriter(writer.Get(), problem))
  {
    return false;
  }
  if (options.header.empty())
  {
    return true;
  }
  // vtkOBJWriter takes no comment: the header goes first as a "#" line (the unit of an export).
  std::string text;
  {
    std::ifstream in(file, std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof())
    {
      problem = "cannot read the written OBJ back to add its header";
      return false;
    }
  }
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << "# " << OneLine(options.header, 200) << "\n" << text;
  out.flush();
  if (!out)
  {
    problem = "write failed (adding the OBJ header)";
    return false;
  }
  return true;
}

bool WritePlyMesh(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions& options,
  std::string& problem)
{
  vtkNew<vtkPLYWriter> writer;
  writer->SetInputData(mesh);
  writer->SetFileName(file.c_str());
  writer->SetFileTypeToBinary();
  if (!options.header.empty())
  {
    writer->AddComment(OneLine(options.header, 200)); // the unit of an export
  }
  return RunWriter(writer.Get(), problem);
}

bool WriteVtpMesh(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions&,
  std::string& problem)
{
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(mesh);
  writer->SetFileName(file.c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->SetHeaderTypeToUInt64();
  writer->SetCompressorTypeToZLib();
  return RunWriter(writer.Get(), problem);
}

bool WriteLegacyVtkMesh(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions& options,
  std::string& problem)
{
  vtkNew<vtkPolyDataWriter> writer;
  writer->SetInputData(mesh);
  writer->SetFileName(file.c_str());
  writer->SetFileTypeToBinary();
  const std::string header = OneLine(options.header.empty() ? "bender mesh" : options.header, 250);
  writer->SetHeader(header.c_str());
  return RunWriter(writer.Get(), problem);
}

bool WriteOffMesh(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions& options,
  std::string& problem)
{
  return WriteOff(mesh, file, OneLine(options.header, 1000), problem);
}

bool WriteSmeshMesh(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions&,
  std::string& problem)
{
  return WriteTetgenMesh(mesh, file, TetgenFormat::Smesh, problem);
}

bool WritePolyMesh(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions&,
  std::string& problem)
{
  return WriteTetgenMesh(mesh, file, TetgenFormat::Poly, problem);
}

} // namespace io_detail
} // namespace bender
