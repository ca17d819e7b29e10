#include "MeshReaders.h"

#include "InputValidation.h"
#include "OffFormat.h"
#include "PlyValidation.h"
#include "StringUtil.h"
#include "VtkMessageGuard.h"

#include <vtkCellData.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPLYReader.h>
#include <vtkPointData.h>
#include <vtkPolyDataReader.h>
#include <vtkSTLReader.h>
#include <vtkXMLPolyDataReader.h>
#include <vtksys/SystemTools.hxx>

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace bender
{
namespace io_detail
{

namespace
{

bool LooksLikeText(const std::string& bytes)
{
  std::size_t odd = 0;
  for (const char c : bytes)
  {
    const auto u = static_cast<unsigned char>(c);
    if (u == 0)
    {
      return false;
    }
    if (u < 32 && u != '\n' && u != '\r' && u != '\t' && u != '\f' && u != '\v')
    {
      ++odd;
    }
  }
  return odd * 20 <= bytes.size();
}

// vtkOBJReader reads "v nan 0 0" or "v 1 x 0" as some number without complaint: check the
// vertex lines first, so that such a file is refused with its line number.
void CheckObjVertices(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::size_t lineNumber = 0;
  while (std::getline(in, line))
  {
    ++lineNumber;
    if (line.find('\0') != std::string::npos)
    {
      FailMesh(path, "not an OBJ file (binary content)");
    }
    if (line.size() < 2 || line[0] != 'v' || (line[1] != ' ' && line[1] != '\t'))
    {
      continue;
    }
    const char* cursor = line.c_str() + 2;
    const char* end = line.c_str() + line.size();
    for (int c = 0; c < 3; ++c)
    {
      while (cursor < end && std::isspace(static_cast<unsigned char>(*cursor)))
      {
        ++cursor;
      }
      if (cursor < end && *cursor == '+')
      {
        ++cursor;
      }
      double value = 0;
      const auto result = std::from_chars(cursor, end, value);
      if (result.ec == std::errc::result_out_of_range)
      {
        FailMesh(path, "line " + std::to_string(lineNumber) + ": non-finite coordinate");
      }
      if (result.ec != std::errc() ||
        (result.ptr < end && !std::isspace(static_cast<unsigned char>(*result.ptr))))
      {
        FailMesh(
          path, "line " + std::to_string(lineNumber) + ": expected 3 coordinates after \"v\"");
      }
      if (!std::isfinite(value))
      {
        FailMesh(path, "line " + std::to_string(lineNumber) + ": non-finite coordinate");
      }
      cursor = result.ptr;
    }
  }
}

// vtkOBJReader (VTK 9.1) passes the file's "vt" and "vn" lists on as point data whenever the
// faces index them like the vertices, also when the file lists fewer of them than vertices,
// and gives "GroupIds" one value per face although its output also holds the "l" and "p"
// elements as cells. The geometry is sound: such arrays are dropped (CheckMesh would refuse
// them).
void DropMismatchedObjArrays(vtkPolyData* mesh)
{
  const std::array<std::pair<vtkFieldData*, vtkIdType>, 2> attributes{ {
    { mesh->GetPointData(), mesh->GetNumberOfPoints() },
    { mesh->GetCellData(), mesh->GetNumberOfCells() },
  } };
  for (const auto& [data, expected] : attributes)
  {
    for (int a = data->GetNumberOfArrays() - 1; a >= 0; --a)
    {
      if (data->GetAbstractArray(a)->GetNumberOfTuples() != expected)
      {
        data->RemoveArray(a);
      }
    }
  }
}

} // namespace

vtkSmartPointer<vtkPolyData> ReadStlMesh(const std::string& path, std::uintmax_t size)
{
  std::string head(static_cast<std::size_t>(std::min<std::uintmax_t>(size, 1024)), '\0');
  {
    std::ifstream in(path, std::ios::binary);
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    if (!in && !in.eof())
    {
      FailMesh(path, "cannot read the file");
    }
  }
  std::size_t first = 0;
  while (first < head.size() && std::isspace(static_cast<unsigned char>(head[first])))
  {
    ++first;
  }
  const bool startsWithSolid = ToLower(head.substr(first, 5)) == "solid";
  const bool text = LooksLikeText(head);

  bool binary = false;
  if (size >= 84)
  {
    const auto* bytes = reinterpret_cast<const unsigned char*>(head.data());
    const std::uint64_t triangles = static_cast<std::uint64_t>(bytes[80]) |
      (static_cast<std::uint64_t>(bytes[81]) << 8) | (static_cast<std::uint64_t>(bytes[82]) << 16) |
      (static_cast<std::uint64_t>(bytes[83]) << 24);
    const std::uint64_t expected = 84 + 50 * triangles;
    if (expected == size)
    {
      binary = true; // exact size: binary even when the header starts with "solid"
    }
    else if (!(startsWithSolid && text))
    {
      if (text)
      {
        FailMesh(path, "not an STL file (text that does not start with \"solid\")");
      }
      if (size < expected)
      {
        std::ostringstream msg;
        msg << "truncated binary STL (header says " << triangles << " triangles, file holds "
            << (size - 84) / 50 << ")";
        FailMesh(path, msg.str());
      }
      // Longer than announced: some exporters pad binary STL files by a few bytes; more than
      // one record's worth is not padding (vtkSTLReader would read the extra bytes as
      // triangles: 2 GB of zeros became 43 million of them).
      if (size - expected >= 50)
      {
        std::ostringstream msg;
        msg << "binary STL longer than its header says (" << triangles << " triangles, "
            << size - expected << " extra bytes)";
        FailMesh(path, msg.str());
      }
      binary = true;
    }
  }
  else if (!(startsWithSolid && text))
  {
    std::ostringstream msg;
    msg << "not an STL file (" << size << " bytes: too short for binary STL, not ASCII STL)";
    FailMesh(path, msg.str());
  }

  // vtkSTLReader decides by itself how to read the file (vtksys DetectFileType: binary when
  // 5 % or more of the first 256 bytes are neither printable ASCII nor tab, CR or LF). An ASCII
  // file it would read as binary (a solid name of bytes >= 128) would have the text after the
  // header read as a triangle count (19 GB asked for); a binary file it would read as text is
  // checked as the ASCII STL that VTK will parse.
  const bool vtkReadsText =
    vtksys::SystemTools::DetectFileType(path.c_str()) == vtksys::SystemTools::FileTypeText;
  if (!binary || vtkReadsText)
  {
    // VTK 9.1's ASCII STL parser asks for gigabytes or misreads a malformed facet.
    std::string problem;
    if (!CheckAsciiStl(ReadWholeFile(path), problem))
    {
      FailMesh(path, problem);
    }
  }
  if (!binary && !vtkReadsText)
  {
    FailMesh(path,
      "ASCII STL with too many bytes that are not printable ASCII in its first 256 bytes (the "
      "STL reader would take it for binary)");
  }
  binary = binary && !vtkReadsText;
  VtkMessageGuard guard;
  vtkNew<vtkSTLReader> reader;
  guard.Watch(reader);
  reader->SetFileName(path.c_str());
  // STL triangles are independent: weld exactly coincident corners into shared vertices.
  reader->MergingOn();
  reader->ScalarTagsOff();
  auto mesh = RunReader(path, reader.Get(), guard);
  if (mesh->GetNumberOfPolys() == 0 && !binary)
  {
    FailMesh(path, "ASCII STL without any facet");
  }
  return mesh;
}

vtkSmartPointer<vtkPolyData> ReadObjMesh(const std::string& path, std::uintmax_t)
{
  CheckObjVertices(path);
  // vtkOBJReader reads normals and texture coordinates by index without checking them.
  {
    std::string problem;
    if (!CheckObj(ReadWholeFile(path), problem))
    {
      FailMesh(path, problem);
    }
  }
  VtkMessageGuard guard;
  vtkNew<vtkOBJReader> reader;
  guard.Watch(reader);
  reader->SetFileName(path.c_str());
  vtkSmartPointer<vtkPolyData> mesh = RunReader(path, reader.Get(), guard);
  DropMismatchedObjArrays(mesh);
  return mesh;
}

vtkSmartPointer<vtkPolyData> ReadPlyMesh(const std::string& path, std::uintmax_t)
{
  VtkMessageGuard guard;
  if (!vtkPLYReader::CanReadFile(path.c_str()))
  {
    FailMesh(path, "not a PLY file (no valid \"ply\" header)");
  }
  std::string problem;
  if (!CheckPlyStructure(path, problem))
  {
    FailMesh(path, problem);
  }
  vtkNew<vtkPLYReader> reader;
  guard.Watch(reader);
  reader->SetFileName(path.c_str());
  return RunReader(path, reader.Get(), guard);
}

vtkSmartPointer<vtkPolyData> ReadVtpMesh(const std::string& path, std::uintmax_t)
{
  // vtkXMLReader divides by the header word size it reads and allocates what the counts say.
  {
    std::string problem;
    if (!CheckVtkXml(ReadWholeFile(path), "PolyData", MaxMeshFileBytes * 4, problem))
    {
      FailMesh(path, problem);
    }
  }
  VtkMessageGuard guard;
  vtkNew<vtkXMLPolyDataReader> reader;
  guard.Watch(reader);
  if (!reader->CanReadFile(path.c_str()))
  {
    FailMesh(path, "not a VTK XML PolyData file");
  }
  reader->SetFileName(path.c_str());
  return RunReader(path, reader.Get(), guard, true);
}

vtkSmartPointer<vtkPolyData> ReadLegacyVtkMesh(const std::string& path, std::uintmax_t)
{
  // vtkDataReader trusts the counts it reads (a short or non-numeric POLYGONS section, or
  // 5.1 offsets out of range, crash it or the cell code after it): walk the whole file first.
  {
    std::string problem;
    if (!CheckLegacyVtk(ReadWholeFile(path), problem))
    {
      FailMesh(path, problem);
    }
  }
  VtkMessageGuard guard;
  vtkNew<vtkPolyDataReader> reader;
  guard.Watch(reader);
  reader->SetFileName(path.c_str());
  if (!reader->IsFilePolyData())
  {
    std::string message = "not a legacy VTK polydata file";
    if (guard.HasError())
    {
      message += " (" + TidyVtkMessage(path, guard.Message()) + ")";
    }
    FailMesh(path, message);
  }
  reader->ReadAllScalarsOn();
  reader->ReadAllVectorsOn();
  reader->ReadAllNormalsOn();
  reader->ReadAllTensorsOn();
  reader->ReadAllColorScalarsOn();
  reader->ReadAllTCoordsOn();
  reader->ReadAllFieldsOn();
  return RunReader(path, reader.Get(), guard, true);
}

vtkSmartPointer<vtkPolyData> ReadOffMesh(const std::string& path, std::uintmax_t)
{
  try
  {
    return ReadOff(path);
  }
  catch (const OffError& e)
  {
    FailMesh(path, e.what());
  }
}

} // namespace io_detail
} // namespace bender
