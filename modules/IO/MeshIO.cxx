#include "MeshIO.h"

#include "FileUtilities.h"
#include "InputValidation.h"
#include "OffFormat.h"
#include "PlyValidation.h"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkErrorCode.h>
#include <vtkExecutive.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkOBJWriter.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPLYReader.h>
#include <vtkPLYWriter.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkPolyDataWriter.h>
#include <vtkSTLReader.h>
#include <vtkSTLWriter.h>
#include <vtkTriangleFilter.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtk_loguru.h>
#include <vtksys/SystemTools.hxx>

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <mutex>
#include <sstream>
#include <tuple>
#include <vector>

namespace bender
{

namespace
{

using io_detail::DisplayName;

[[noreturn]] void Fail(const std::string& path, const std::string& problem)
{
  // File names and problems may quote file bytes: never let a control byte or an escape
  // sequence reach the terminal.
  throw MeshIOError(
    io_detail::QuoteBytes(DisplayName(path), 200) + ": " + io_detail::QuoteBytes(problem, 400));
}

// A VTK message fit for a one-line error: the file's base name instead of its full path
// (readers quote it), no control or binary bytes (readers quote garbage), at most 200 bytes.
std::string Tidy(const std::string& path, std::string message)
{
  if (message.empty())
  {
    return message;
  }
  // The display name may be the path itself (a bare file name) or contain it: search on
  // after each replacement, never at the same spot again.
  const std::string display = DisplayName(path);
  for (std::size_t at = message.find(path); !path.empty() && at != std::string::npos;
       at = message.find(path, at + display.size()))
  {
    message.replace(at, path.size(), display);
  }
  return io_detail::CleanMessage(message, 200);
}

// The whole file, for the pre-validators (the size was checked against the budget).
std::string ReadAll(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    Fail(path, "cannot be opened for reading");
  }
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad())
  {
    Fail(path, "cannot read the file");
  }
  return data;
}

// VTK's "ERROR: In file, line N\nvtkClass (0x...): text\n\n" reduced to "text".
std::string CleanVtkMessage(const char* raw)
{
  std::string text = raw ? raw : "";
  std::istringstream lines(text);
  std::string line;
  std::string result;
  while (std::getline(lines, line))
  {
    if (line.rfind("ERROR: In ", 0) == 0 || line.rfind("Warning: In ", 0) == 0 ||
      line.rfind("Generic Warning: In ", 0) == 0)
    {
      continue;
    }
    const std::size_t marker = line.find("): ");
    if (marker != std::string::npos && line.rfind("vtk", 0) == 0)
    {
      line = line.substr(marker + 3);
    }
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back())))
    {
      line.pop_back();
    }
    if (!line.empty())
    {
      result += result.empty() ? line : "; " + line;
    }
  }
  return result.empty() ? "unknown VTK error" : result;
}

// An output window that keeps what it is given, so that messages from VTK helper objects
// without observers (parsers, vtkGenericWarningMacro) end up in our error instead of on
// stderr.
class CapturingOutputWindow : public vtkOutputWindow
{
public:
  static CapturingOutputWindow* New();
  vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override
  {
    if (!text)
    {
      return;
    }
    switch (this->GetCurrentMessageType())
    {
      case MESSAGE_TYPE_ERROR:
        this->Errors.push_back(CleanVtkMessage(text));
        break;
      case MESSAGE_TYPE_WARNING:
      case MESSAGE_TYPE_GENERIC_WARNING:
        this->Warnings.push_back(CleanVtkMessage(text));
        break;
      default:
        break;
    }
  }
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;

protected:
  CapturingOutputWindow() = default;
};
vtkStandardNewMacro(CapturingOutputWindow);

// For its lifetime: collects the errors and warnings of the watched VTK objects (through
// observers, which also keeps them off the output window), routes the global output window
// into a buffer and mutes VTK's logger on stderr, restoring both afterwards. The output
// window and the logger are process-wide, so guards run one at a time.
class VtkMessageGuard
{
public:
  VtkMessageGuard()
    : Lock(Mutex())
  {
    this->Previous = vtkOutputWindow::GetInstance();
    vtkOutputWindow::SetInstance(this->Capture);
    this->PreviousStderrVerbosity = vtkloguru::g_stderr_verbosity;
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  }
  ~VtkMessageGuard()
  {
    vtkLogger::SetStderrVerbosity(static_cast<vtkLogger::Verbosity>(this->PreviousStderrVerbosity));
    vtkOutputWindow::SetInstance(this->Previous);
  }
  VtkMessageGuard(const VtkMessageGuard&) = delete;
  VtkMessageGuard& operator=(const VtkMessageGuard&) = delete;

  /// Watches an algorithm and its executive (which reports "returned failure" on its own).
  void Watch(vtkAlgorithm* algorithm)
  {
    vtkNew<vtkCallbackCommand> callback;
    callback->SetClientData(this);
    callback->SetCallback(&VtkMessageGuard::OnEvent);
    for (vtkObject* object :
      { static_cast<vtkObject*>(algorithm), static_cast<vtkObject*>(algorithm->GetExecutive()) })
    {
      object->AddObserver(vtkCommand::ErrorEvent, callback);
      object->AddObserver(vtkCommand::WarningEvent, callback);
    }
  }

  bool HasError() const { return !this->Errors.empty() || !this->Capture->Errors.empty(); }
  bool HasWarning() const { return !this->Warnings.empty() || !this->Capture->Warnings.empty(); }
  /// The first error seen, else the first warning; empty when there was neither.
  std::string Message() const
  {
    const std::vector<std::string>* lists[] = {
      &this->Errors, &this->Capture->Errors, &this->Warnings, &this->Capture->Warnings
    };
    for (const auto* list : lists)
    {
      if (!list->empty())
      {
        return list->front();
      }
    }
    return {};
  }

private:
  static std::mutex& Mutex()
  {
    static std::mutex mutex;
    return mutex;
  }
  static void OnEvent(vtkObject*, unsigned long event, void* clientData, void* callData)
  {
    auto* self = static_cast<VtkMessageGuard*>(clientData);
    const std::string text = CleanVtkMessage(static_cast<const char*>(callData));
    // The executive's "returned failure for request" says nothing the reader did not say.
    if (text.find("returned failure for request") != std::string::npos)
    {
      self->ExecutiveFailure = true;
      return;
    }
    (event == vtkCommand::ErrorEvent ? self->Errors : self->Warnings).push_back(text);
  }

  std::unique_lock<std::mutex> Lock;
  vtkSmartPointer<vtkOutputWindow> Previous;
  vtkNew<CapturingOutputWindow> Capture;
  int PreviousStderrVerbosity = 0;
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;

public:
  bool ExecutiveFailure = false;
};

std::string Lowercase(std::string text)
{
  for (char& c : text)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return text;
}

const char* const SupportedExtensions = ".stl, .obj, .ply, .vtp, .vtk, .off";

// Every point finite, every cell index in range: a reader that returns less is a bad file.
void CheckMesh(const std::string& path, vtkPolyData* mesh)
{
  if (!mesh || !mesh->GetPoints() || mesh->GetNumberOfPoints() == 0)
  {
    Fail(path, "no points in the file");
  }
  const vtkIdType n = mesh->GetNumberOfPoints();
  vtkPoints* points = mesh->GetPoints();
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      std::ostringstream msg;
      msg << "point " << i << " has a non-finite coordinate (" << p[0] << ", " << p[1] << ", "
          << p[2] << ")";
      Fail(path, msg.str());
    }
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
      Fail(path, msg.str());
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
        Fail(path, msg.str());
      }
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

// Runs a configured VTK reader and returns its output, or throws with its first error.
// warningsAreErrors: for the VTK formats, whose readers only warn about truncated data.
template<typename Reader>
vtkSmartPointer<vtkPolyData> RunReader(const std::string& path,
  Reader* reader,
  VtkMessageGuard& guard,
  bool warningsAreErrors = false)
{
  reader->Update();
  const unsigned long code = reader->GetErrorCode();
  if (guard.HasError() || code != 0 || guard.ExecutiveFailure ||
    (warningsAreErrors && guard.HasWarning()))
  {
    std::string message = Tidy(path, guard.Message());
    if (message.empty())
    {
      message = std::string("read error (") +
        vtkErrorCode::GetStringFromErrorCode(static_cast<unsigned long>(code)) + ")";
    }
    Fail(path, message);
  }
  vtkSmartPointer<vtkPolyData> output = reader->GetOutput();
  if (!output || output->GetNumberOfPoints() == 0)
  {
    const std::string message = Tidy(path, guard.Message());
    Fail(
      path, message.empty() ? "no points in the file" : "no points in the file (" + message + ")");
  }
  // Detach from the reader so that the caller owns plain data.
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(output);
  return mesh;
}

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

vtkSmartPointer<vtkPolyData> ReadStl(const std::string& path, std::uintmax_t size)
{
  std::string head(static_cast<std::size_t>(std::min<std::uintmax_t>(size, 1024)), '\0');
  {
    std::ifstream in(path, std::ios::binary);
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    if (!in && !in.eof())
    {
      Fail(path, "cannot read the file");
    }
  }
  std::size_t first = 0;
  while (first < head.size() && std::isspace(static_cast<unsigned char>(head[first])))
  {
    ++first;
  }
  const bool startsWithSolid = Lowercase(head.substr(first, 5)) == "solid";
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
        Fail(path, "not an STL file (text that does not start with \"solid\")");
      }
      if (size < expected)
      {
        std::ostringstream msg;
        msg << "truncated binary STL (header says " << triangles << " triangles, file holds "
            << (size - 84) / 50 << ")";
        Fail(path, msg.str());
      }
      // Longer than announced: some exporters pad binary STL files by a few bytes; more than
      // one record's worth is not padding (vtkSTLReader would read the extra bytes as
      // triangles: 2 GB of zeros became 43 million of them).
      if (size - expected >= 50)
      {
        std::ostringstream msg;
        msg << "binary STL longer than its header says (" << triangles << " triangles, "
            << size - expected << " extra bytes)";
        Fail(path, msg.str());
      }
      binary = true;
    }
  }
  else if (!(startsWithSolid && text))
  {
    std::ostringstream msg;
    msg << "not an STL file (" << size << " bytes: too short for binary STL, not ASCII STL)";
    Fail(path, msg.str());
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
    if (!io_detail::CheckAsciiStl(ReadAll(path), problem))
    {
      Fail(path, problem);
    }
  }
  if (!binary && !vtkReadsText)
  {
    Fail(path,
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
    Fail(path, "ASCII STL without any facet");
  }
  return mesh;
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
      Fail(path, "not an OBJ file (binary content)");
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
        Fail(path, "line " + std::to_string(lineNumber) + ": non-finite coordinate");
      }
      if (result.ec != std::errc() ||
        (result.ptr < end && !std::isspace(static_cast<unsigned char>(*result.ptr))))
      {
        Fail(path, "line " + std::to_string(lineNumber) + ": expected 3 coordinates after \"v\"");
      }
      if (!std::isfinite(value))
      {
        Fail(path, "line " + std::to_string(lineNumber) + ": non-finite coordinate");
      }
      cursor = result.ptr;
    }
  }
}

vtkSmartPointer<vtkPolyData> ReadObj(const std::string& path)
{
  CheckObjVertices(path);
  // vtkOBJReader reads normals and texture coordinates by index without checking them.
  {
    std::string problem;
    if (!io_detail::CheckObj(ReadAll(path), problem))
    {
      Fail(path, problem);
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

vtkSmartPointer<vtkPolyData> ReadPly(const std::string& path)
{
  VtkMessageGuard guard;
  if (!vtkPLYReader::CanReadFile(path.c_str()))
  {
    Fail(path, "not a PLY file (no valid \"ply\" header)");
  }
  std::string problem;
  if (!io_detail::CheckPlyStructure(path, problem))
  {
    Fail(path, problem);
  }
  vtkNew<vtkPLYReader> reader;
  guard.Watch(reader);
  reader->SetFileName(path.c_str());
  return RunReader(path, reader.Get(), guard);
}

vtkSmartPointer<vtkPolyData> ReadVtp(const std::string& path)
{
  // vtkXMLReader divides by the header word size it reads and allocates what the counts say.
  {
    std::string problem;
    if (!io_detail::CheckVtkXml(
          ReadAll(path), "PolyData", io_detail::MaxMeshFileBytes * 4, problem))
    {
      Fail(path, problem);
    }
  }
  VtkMessageGuard guard;
  vtkNew<vtkXMLPolyDataReader> reader;
  guard.Watch(reader);
  if (!reader->CanReadFile(path.c_str()))
  {
    Fail(path, "not a VTK XML PolyData file");
  }
  reader->SetFileName(path.c_str());
  return RunReader(path, reader.Get(), guard, true);
}

vtkSmartPointer<vtkPolyData> ReadLegacyVtk(const std::string& path)
{
  // vtkDataReader trusts the counts it reads (a short or non-numeric POLYGONS section, or
  // 5.1 offsets out of range, crash it or the cell code after it): walk the whole file first.
  {
    std::string problem;
    if (!io_detail::CheckLegacyVtk(ReadAll(path), problem))
    {
      Fail(path, problem);
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
      message += " (" + Tidy(path, guard.Message()) + ")";
    }
    Fail(path, message);
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

std::string OneLine(const std::string& text, std::size_t maxLength)
{
  std::string line;
  for (const char c : text)
  {
    line += (c == '\n' || c == '\r' || c == '\0') ? ' ' : c;
  }
  if (line.size() > maxLength)
  {
    line.resize(maxLength);
  }
  return line;
}

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

// Runs a configured VTK writer (vtkWriter or vtkXMLWriter), reporting its first error.
template<typename Writer>
bool RunWriter(Writer* writer, std::string& problem)
{
  VtkMessageGuard guard;
  guard.Watch(writer);
  const int ok = writer->Write();
  if (!ok || guard.HasError() || writer->GetErrorCode() != 0)
  {
    problem = guard.Message().empty() ? std::string() : io_detail::CleanMessage(guard.Message());
    if (problem.empty())
    {
      problem = std::string("write error (") +
        vtkErrorCode::GetStringFromErrorCode(writer->GetErrorCode()) + ")";
    }
    return false;
  }
  return true;
}

} // namespace

static vtkSmartPointer<vtkPolyData> ReadMeshUnchecked(const std::string& path)
{
  std::uintmax_t size = 0;
  std::string problem;
  if (!io_detail::CheckReadableFile(path, size, problem))
  {
    Fail(path, problem);
  }
  if (size > io_detail::MaxMeshFileBytes)
  {
    Fail(path,
      "larger than the " + std::to_string(io_detail::MaxMeshFileBytes >> 20) +
        " MiB limit for mesh files (" + std::to_string(size >> 20) + " MiB)");
  }
  const std::string ext = io_detail::LowerExtension(path);
  vtkSmartPointer<vtkPolyData> mesh;
  if (ext == ".stl")
  {
    mesh = ReadStl(path, size);
  }
  else if (ext == ".obj")
  {
    mesh = ReadObj(path);
  }
  else if (ext == ".ply")
  {
    mesh = ReadPly(path);
  }
  else if (ext == ".vtp")
  {
    mesh = ReadVtp(path);
  }
  else if (ext == ".vtk")
  {
    mesh = ReadLegacyVtk(path);
  }
  else if (ext == ".off")
  {
    try
    {
      mesh = io_detail::ReadOff(path);
    }
    catch (const io_detail::OffError& e)
    {
      Fail(path, e.what());
    }
  }
  else
  {
    Fail(path,
      (ext.empty() ? std::string("no file extension") : "unknown extension \"" + ext + "\"") +
        " (meshes are read from " + SupportedExtensions + ")");
  }
  return mesh;
}

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path)
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
    Fail(path, "corrupt file (its sizes ask for more memory than there is)");
  }
  catch (const std::exception& e)
  {
    Fail(path, std::string("corrupt file (") + e.what() + ")");
  }
  CheckMesh(path, mesh);
  return mesh;
}

void WriteMesh(vtkPolyData* mesh, const std::string& path, const MeshWriteOptions& options)
{
  if (!mesh || !mesh->GetPoints() || mesh->GetNumberOfPoints() == 0)
  {
    Fail(path, "refusing to write a mesh without points");
  }
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      Fail(path,
        "refusing to write a mesh with a non-finite coordinate (point " + std::to_string(i) + ")");
    }
  }
  const std::string ext = io_detail::LowerExtension(path);
  // STL, OBJ and PLY store single precision: a coordinate beyond the float range would be
  // written as inf.
  if (ext == ".stl" || ext == ".obj" || ext == ".ply")
  {
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      double p[3];
      mesh->GetPoint(i, p);
      for (const double c : p)
      {
        if (std::fabs(c) > static_cast<double>(std::numeric_limits<float>::max()))
        {
          std::ostringstream msg;
          msg << "refusing to write point " << i << ": coordinate " << c
              << " is beyond the single-precision range of " << ext << " files";
          Fail(path, msg.str());
        }
      }
    }
  }

  std::function<bool(const std::string&, std::string&)> produce;
  if (ext == ".stl")
  {
    produce = [&](const std::string& temp, std::string& problem)
    {
      vtkSmartPointer<vtkPolyData> triangles = Triangulated(mesh);
      if (triangles->GetNumberOfPolys() == 0)
      {
        problem = "STL holds triangles only, and the mesh has none";
        return false;
      }
      vtkNew<vtkSTLWriter> writer;
      writer->SetInputData(triangles);
      writer->SetFileName(temp.c_str());
      if (options.stlEncoding == StlEncoding::Binary)
      {
        writer->SetFileTypeToBinary();
        std::string header = OneLine(options.header, 80);
        // A binary header that starts with "solid" makes other readers take it for ASCII.
        if (Lowercase(header.substr(0, 5)) == "solid")
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
    };
  }
  else if (ext == ".obj")
  {
    produce = [&](const std::string& temp, std::string& problem)
    {
      vtkNew<vtkOBJWriter> writer;
      writer->SetInputData(mesh);
      writer->SetFileName(temp.c_str());
      return RunWriter(writer.Get(), problem);
    };
  }
  else if (ext == ".ply")
  {
    produce = [&](const std::string& temp, std::string& problem)
    {
      vtkNew<vtkPLYWriter> writer;
      writer->SetInputData(mesh);
      writer->SetFileName(temp.c_str());
      writer->SetFileTypeToBinary();
      return RunWriter(writer.Get(), problem);
    };
  }
  else if (ext == ".vtp")
  {
    produce = [&](const std::string& temp, std::string& problem)
    {
      vtkNew<vtkXMLPolyDataWriter> writer;
      writer->SetInputData(mesh);
      writer->SetFileName(temp.c_str());
      writer->SetDataModeToAppended();
      writer->EncodeAppendedDataOff();
      writer->SetHeaderTypeToUInt64();
      writer->SetCompressorTypeToZLib();
      return RunWriter(writer.Get(), problem);
    };
  }
  else if (ext == ".vtk")
  {
    produce = [&](const std::string& temp, std::string& problem)
    {
      vtkNew<vtkPolyDataWriter> writer;
      writer->SetInputData(mesh);
      writer->SetFileName(temp.c_str());
      writer->SetFileTypeToBinary();
      const std::string header =
        OneLine(options.header.empty() ? "bender mesh" : options.header, 250);
      writer->SetHeader(header.c_str());
      return RunWriter(writer.Get(), problem);
    };
  }
  else if (ext == ".off")
  {
    produce = [&](const std::string& temp, std::string& problem)
    { return io_detail::WriteOff(mesh, temp, OneLine(options.header, 1000), problem); };
  }
  else
  {
    Fail(path,
      (ext.empty() ? std::string("no file extension") : "unknown extension \"" + ext + "\"") +
        " (meshes are written as " + SupportedExtensions + ")");
  }

  std::string problem;
  if (!AtomicWrite(path, produce, problem))
  {
    Fail(path, problem);
  }
}

} // namespace bender
