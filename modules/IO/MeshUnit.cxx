#include "MeshUnit.h"

#include "StringUtil.h"

#include <vtkFieldData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>

#include <cctype>
#include <fstream>
#include <string_view>

namespace bender
{

namespace
{

constexpr const char* UnitArrayName = "Unit";
constexpr std::size_t HeadBytes = 4096;

vtkStringArray* UnitArray(vtkPolyData* mesh)
{
  if (!mesh || !mesh->GetFieldData())
  {
    return nullptr;
  }
  auto* array = vtkStringArray::SafeDownCast(mesh->GetFieldData()->GetAbstractArray(UnitArrayName));
  return array && array->GetNumberOfValues() > 0 ? array : nullptr;
}

// "m" or "mm" when `text` holds Bender's statement ("... bender ...: frame LPS, unit m"):
// the word after the last ", unit " of a text that names bender.
std::string UnitIn(std::string_view text)
{
  if (ToLower(text).find("bender") == std::string::npos)
  {
    return {};
  }
  const std::string_view key = ", unit ";
  const std::size_t at = text.rfind(key);
  if (at == std::string_view::npos)
  {
    return {};
  }
  std::size_t end = at + key.size();
  while (end < text.size() && std::isalpha(static_cast<unsigned char>(text[end])))
  {
    ++end;
  }
  const std::string unit(text.substr(at + key.size(), end - at - key.size()));
  return unit == "m" || unit == "mm" ? unit : std::string();
}

// The unit stated on one of the lines of `text` (lines end at '\n', '\r' or '\0').
std::string UnitOnALine(std::string_view text)
{
  std::size_t start = 0;
  while (start < text.size())
  {
    std::size_t end = text.find_first_of(std::string_view("\n\r\0", 3), start);
    if (end == std::string_view::npos)
    {
      end = text.size();
    }
    const std::string unit = UnitIn(text.substr(start, end - start));
    if (!unit.empty())
    {
      return unit;
    }
    start = end + 1;
  }
  return {};
}

// An ASCII STL of named solids states its unit on the first "endsolid" line.
std::string UnitOfFirstSolid(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  while (std::getline(in, line))
  {
    const std::string_view trimmed = Trim(line);
    if (StartsWith(trimmed, "endsolid"))
    {
      return UnitIn(trimmed);
    }
  }
  return {};
}

} // namespace

std::string StatedLengthUnit(const std::string& path, vtkPolyData* mesh)
{
  if (vtkStringArray* array = UnitArray(mesh))
  {
    const std::string unit = array->GetValue(0);
    return unit == "m" || unit == "mm" ? unit : std::string();
  }
  std::string head(HeadBytes, '\0');
  {
    std::ifstream in(path, std::ios::binary);
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
  }
  if (LowerExtension(path) != ".stl")
  {
    return UnitOnALine(head);
  }
  // STL: the binary header (80 bytes, triangles follow) or the ASCII "solid" line, else the
  // first "endsolid" line of an ASCII file.
  const std::string header = head.substr(0, 80);
  const std::string unit = UnitOnALine(header);
  // (Binary files may start with "solid" too; their triangles hold zero bytes.)
  const bool ascii =
    StartsWith(ToLower(Trim(header)), "solid") && head.find('\0') == std::string::npos;
  return unit.empty() && ascii ? UnitOfFirstSolid(path) : unit;
}

std::string ToMillimetres(const std::string& path, vtkPolyData* mesh)
{
  const std::string unit = StatedLengthUnit(path, mesh);
  if (unit != "m" || !mesh || !mesh->GetPoints())
  {
    return unit;
  }
  vtkPoints* points = mesh->GetPoints();
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    points->SetPoint(i, 1000.0 * p[0], 1000.0 * p[1], 1000.0 * p[2]);
  }
  points->Modified();
  if (vtkStringArray* array = UnitArray(mesh))
  {
    array->SetValue(0, "mm");
  }
  return unit;
}

} // namespace bender
