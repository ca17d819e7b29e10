#include "OffFormat.h"

#include "CoordinateRange.h"
#include "StringUtil.h"
#include "ValidationText.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <limits>
#include <string_view>
#include <vector>

namespace bender
{
namespace io_detail
{

namespace
{

// Data lines of the file: comments ("#" to the end of the line) and blank lines skipped.
class LineReader
{
public:
  explicit LineReader(const std::string& text)
    : Text(text)
  {
  }

  bool Next(std::string_view& line)
  {
    while (this->Pos < this->Text.size())
    {
      std::size_t end = this->Text.find('\n', this->Pos);
      if (end == std::string::npos)
      {
        end = this->Text.size();
      }
      std::string_view raw(this->Text.data() + this->Pos, end - this->Pos);
      this->Pos = end + 1;
      ++this->LineNumber;
      const std::size_t hash = raw.find('#');
      if (hash != std::string_view::npos)
      {
        raw = raw.substr(0, hash);
      }
      raw = Trim(raw);
      if (!raw.empty())
      {
        line = raw;
        return true;
      }
    }
    return false;
  }
  std::size_t Line() const { return this->LineNumber; }

private:
  const std::string& Text;
  std::size_t Pos = 0;
  std::size_t LineNumber = 0;
};

// Locale-independent. A value beyond the double range reads as infinity (and is then
// refused as non-finite), one below it as zero.
bool ParseDouble(std::string_view token, double& value)
{
  if (!token.empty() && token.front() == '+')
  {
    token.remove_prefix(1);
  }
  const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
  if (result.ptr != token.data() + token.size())
  {
    return false;
  }
  if (result.ec == std::errc::result_out_of_range)
  {
    const std::size_t e = token.find_first_of("eE");
    const bool tiny = e != std::string_view::npos && e + 1 < token.size() && token[e + 1] == '-';
    const bool negative = !token.empty() && token.front() == '-';
    value = tiny ? 0.0 : std::numeric_limits<double>::infinity();
    value = negative ? -value : value;
    return true;
  }
  return result.ec == std::errc();
}

bool ParseInteger(std::string_view token, long long& value)
{
  if (!token.empty() && token.front() == '+')
  {
    token.remove_prefix(1);
  }
  const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
  return result.ec == std::errc() && result.ptr == token.data() + token.size();
}

[[noreturn]] void FailAt(std::size_t line, const std::string& problem)
{
  throw OffError("line " + std::to_string(line) + ": " + problem);
}

// "OFF" with the optional prefixes of the Geomview family: ST (texture), C (colour),
// N (normal). The extra vertex columns they add are ignored.
bool IsOffKeyword(std::string_view token)
{
  for (std::string_view prefix : { "ST", "C", "N" })
  {
    if (token.substr(0, prefix.size()) == prefix)
    {
      token.remove_prefix(prefix.size());
    }
  }
  return token == "OFF";
}

} // namespace

vtkSmartPointer<vtkPolyData> ReadOff(const std::string& path)
{
  std::string text;
  {
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
      throw OffError("cannot be opened for reading");
    }
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (text.find('\0') != std::string::npos)
  {
    throw OffError("not an ASCII OFF file (binary content)");
  }

  LineReader lines(text);
  std::vector<std::string_view> tokens;
  std::string_view line;
  if (!lines.Next(line))
  {
    throw OffError("no data (only comments or blank lines)");
  }
  SplitWords(line, tokens);
  std::size_t countsAt = 0;
  if (IsOffKeyword(tokens[0]))
  {
    for (std::size_t t = 1; t < tokens.size(); ++t)
    {
      if (tokens[t] == "BINARY")
      {
        FailAt(lines.Line(), "binary OFF is not supported");
      }
    }
    countsAt = 1;
    if (tokens.size() == 1)
    {
      if (!lines.Next(line))
      {
        throw OffError("file ends before the vertex and face counts");
      }
      SplitWords(line, tokens);
      countsAt = 0;
    }
  }
  else
  {
    long long unused;
    if (!ParseInteger(tokens[0], unused))
    {
      std::string keyword(tokens[0].substr(0, 20));
      if (keyword.find("OFF") != std::string::npos)
      {
        FailAt(lines.Line(), "unsupported OFF variant \"" + keyword + "\" (only 3D OFF is read)");
      }
      FailAt(lines.Line(), "not an OFF file (expected \"OFF\", found \"" + keyword + "\")");
    }
  }

  long long vertexCount = -1;
  long long faceCount = -1;
  if (tokens.size() < countsAt + 2 || !ParseInteger(tokens[countsAt], vertexCount) ||
    !ParseInteger(tokens[countsAt + 1], faceCount) || vertexCount < 0 || faceCount < 0)
  {
    FailAt(lines.Line(), "expected the counts \"vertices faces edges\"");
  }
  // Reserve no more than the file can hold (each vertex line takes at least 6 bytes, "0 0 0\n",
  // and each face 8), so that an absurd count ends in "file ends after ..." and not in an
  // allocation failure.
  const auto canHold = [&](long long count, std::size_t bytesPerItem)
  {
    return static_cast<vtkIdType>(
      std::min<long long>(count, static_cast<long long>(text.size() / bytesPerItem)));
  };
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->Allocate(canHold(vertexCount, 6));
  for (long long i = 0; i < vertexCount; ++i)
  {
    if (!lines.Next(line))
    {
      throw OffError("file ends after " + std::to_string(i) + " of " + std::to_string(vertexCount) +
        " vertices");
    }
    SplitWords(line, tokens);
    double p[3];
    if (tokens.size() < 3 || !ParseDouble(tokens[0], p[0]) || !ParseDouble(tokens[1], p[1]) ||
      !ParseDouble(tokens[2], p[2]))
    {
      FailAt(lines.Line(), "expected 3 coordinates");
    }
    if (!InMeshCoordinateRange(p))
    {
      FailAt(lines.Line(), CoordinateRangeProblem(p));
    }
    points->InsertNextPoint(p);
  }

  vtkNew<vtkCellArray> polys;
  polys->AllocateEstimate(canHold(faceCount, 8), 3);
  std::vector<vtkIdType> ids;
  for (long long f = 0; f < faceCount; ++f)
  {
    if (!lines.Next(line))
    {
      throw OffError(
        "file ends after " + std::to_string(f) + " of " + std::to_string(faceCount) + " faces");
    }
    SplitWords(line, tokens);
    long long n = 0;
    if (tokens.empty() || !ParseInteger(tokens[0], n))
    {
      FailAt(lines.Line(), "expected a face (vertex count, then vertex indices)");
    }
    if (n < 3)
    {
      FailAt(lines.Line(), "a face needs at least 3 vertices, found " + std::to_string(n));
    }
    if (static_cast<long long>(tokens.size()) - 1 < n)
    {
      FailAt(lines.Line(),
        "face announces " + std::to_string(n) + " vertices but lists " +
          std::to_string(tokens.size() - 1));
    }
    ids.resize(static_cast<std::size_t>(n));
    for (long long k = 0; k < n; ++k)
    {
      long long index = 0;
      if (!ParseInteger(tokens[static_cast<std::size_t>(k + 1)], index))
      {
        FailAt(lines.Line(),
          "vertex index \"" + std::string(tokens[static_cast<std::size_t>(k + 1)].substr(0, 30)) +
            "\" is not an integer");
      }
      if (index < 0 || index >= vertexCount)
      {
        FailAt(lines.Line(),
          "vertex index " + std::to_string(index) + " out of range (the file has " +
            std::to_string(vertexCount) + " vertices)");
      }
      ids[static_cast<std::size_t>(k)] = static_cast<vtkIdType>(index);
    }
    polys->InsertNextCell(static_cast<vtkIdType>(n), ids.data());
  }
  if (lines.Next(line))
  {
    FailAt(lines.Line(),
      "more data than the header announces (" + std::to_string(vertexCount) + " vertices, " +
        std::to_string(faceCount) + " faces)");
  }

  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  return mesh;
}

namespace
{

void AppendNumber(std::string& out, double value)
{
  char buffer[32];
  // Shortest decimal that reads back as the same double, independent of the C locale.
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

void AppendInteger(std::string& out, long long value)
{
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

} // namespace

bool WriteOff(vtkPolyData* mesh,
  const std::string& path,
  const std::string& header,
  std::string& problem)
{
  const vtkIdType pointCount = mesh->GetNumberOfPoints();
  // Faces: polygons as they are, strips as their triangles (alternating orientation).
  std::vector<std::vector<vtkIdType>> stripTriangles;
  if (vtkCellArray* strips = mesh->GetStrips())
  {
    auto it = vtk::TakeSmartPointer(strips->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType n;
      const vtkIdType* ids;
      it->GetCurrentCell(n, ids);
      for (vtkIdType k = 0; k + 2 < n; ++k)
      {
        if (k % 2 == 0)
        {
          stripTriangles.push_back({ ids[k], ids[k + 1], ids[k + 2] });
        }
        else
        {
          stripTriangles.push_back({ ids[k + 1], ids[k], ids[k + 2] });
        }
      }
    }
  }
  // Polygons of fewer than 3 vertices are not faces: OFF readers (ours included) refuse them.
  vtkIdType polyCount = 0;
  if (vtkCellArray* polys = mesh->GetPolys())
  {
    auto it = vtk::TakeSmartPointer(polys->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      polyCount += it->GetCurrentCell()->GetNumberOfIds() >= 3 ? 1 : 0;
    }
  }
  const long long faceCount =
    static_cast<long long>(polyCount) + static_cast<long long>(stripTriangles.size());

  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out)
  {
    problem = "cannot create the file";
    return false;
  }
  std::string buffer;
  buffer.reserve(1 << 20);
  auto flush = [&]()
  {
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    buffer.clear();
  };

  buffer += "OFF\n";
  if (!header.empty())
  {
    buffer += "# " + header + "\n";
  }
  AppendInteger(buffer, pointCount);
  buffer += ' ';
  AppendInteger(buffer, faceCount);
  buffer += " 0\n";
  for (vtkIdType i = 0; i < pointCount; ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    AppendNumber(buffer, p[0]);
    buffer += ' ';
    AppendNumber(buffer, p[1]);
    buffer += ' ';
    AppendNumber(buffer, p[2]);
    buffer += '\n';
    if (buffer.size() > (1 << 20))
    {
      flush();
    }
  }
  auto appendFace = [&](vtkIdType n, const vtkIdType* ids)
  {
    AppendInteger(buffer, n);
    for (vtkIdType k = 0; k < n; ++k)
    {
      buffer += ' ';
      AppendInteger(buffer, ids[k]);
    }
    buffer += '\n';
    if (buffer.size() > (1 << 20))
    {
      flush();
    }
  };
  if (polyCount > 0)
  {
    auto it = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType n;
      const vtkIdType* ids;
      it->GetCurrentCell(n, ids);
      if (n >= 3)
      {
        appendFace(n, ids);
      }
    }
  }
  for (const auto& triangle : stripTriangles)
  {
    appendFace(3, triangle.data());
  }
  flush();
  out.flush();
  if (!out)
  {
    problem = "write failed (disk full?)";
    return false;
  }
  return true;
}

} // namespace io_detail
} // namespace bender
