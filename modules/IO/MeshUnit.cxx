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
constexpr const char* FrameArrayName = "Frame";
constexpr std::size_t HeadBytes = 4096;

vtkStringArray* StringField(vtkPolyData* mesh, const char* name)
{
  if (!mesh || !mesh->GetFieldData())
  {
    return nullptr;
  }
  auto* array = vtkStringArray::SafeDownCast(mesh->GetFieldData()->GetAbstractArray(name));
  return array && array->GetNumberOfValues() > 0 ? array : nullptr;
}

bool IsUnit(const std::string& word)
{
  return word == "m" || word == "mm";
}

bool IsFrame(const std::string& word)
{
  return word == "LPS" || word == "RAS";
}

// The word after the last `key` of `text`, when `accepted`; else empty.
std::string WordAfter(std::string_view text,
  std::string_view key,
  bool (*accepted)(const std::string&))
{
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
  const std::string word(text.substr(at + key.size(), end - at - key.size()));
  return accepted(word) ? word : std::string();
}

// What `text` states when it holds Bender's statement ("... bender ...: frame RAS, unit m"):
// the word after the last "frame " and after the last ", unit " of a text that names bender.
StatedSpace SpaceIn(std::string_view text)
{
  if (ToLower(text).find("bender") == std::string::npos)
  {
    return {};
  }
  return { WordAfter(text, ", unit ", IsUnit), WordAfter(text, "frame ", IsFrame) };
}

bool StatesAnything(const StatedSpace& space)
{
  return !space.unit.empty() || !space.frame.empty();
}

// What the first of the lines of `text` that states anything states (lines end at '\n', '\r'
// or '\0').
StatedSpace SpaceOnALine(std::string_view text)
{
  std::size_t start = 0;
  while (start < text.size())
  {
    std::size_t end = text.find_first_of(std::string_view("\n\r\0", 3), start);
    if (end == std::string_view::npos)
    {
      end = text.size();
    }
    const StatedSpace space = SpaceIn(text.substr(start, end - start));
    if (StatesAnything(space))
    {
      return space;
    }
    start = end + 1;
  }
  return {};
}

// An ASCII STL of named solids states its unit and frame on the first "endsolid" line.
StatedSpace SpaceOfFirstSolid(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  while (std::getline(in, line))
  {
    const std::string_view trimmed = Trim(line);
    if (StartsWith(trimmed, "endsolid"))
    {
      return SpaceIn(trimmed);
    }
  }
  return {};
}

// What the file's header or comments state (the field data aside).
StatedSpace StatedInText(const std::string& path)
{
  std::string head(HeadBytes, '\0');
  {
    std::ifstream in(path, std::ios::binary);
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
  }
  if (LowerExtension(path) != ".stl")
  {
    return SpaceOnALine(head);
  }
  // STL: the binary header (80 bytes, triangles follow) or the ASCII "solid" line, else the
  // first "endsolid" line of an ASCII file.
  const std::string header = head.substr(0, 80);
  const StatedSpace space = SpaceOnALine(header);
  // (Binary files may start with "solid" too; their triangles hold zero bytes.)
  const bool ascii =
    StartsWith(ToLower(Trim(header)), "solid") && head.find('\0') == std::string::npos;
  return !StatesAnything(space) && ascii ? SpaceOfFirstSolid(path) : space;
}

} // namespace

StatedSpace StatedCoordinates(const std::string& path, vtkPolyData* mesh)
{
  vtkStringArray* unitField = StringField(mesh, UnitArrayName);
  vtkStringArray* frameField = StringField(mesh, FrameArrayName);
  StatedSpace space;
  if (!unitField || !frameField)
  {
    space = StatedInText(path);
  }
  if (unitField)
  {
    const std::string unit = unitField->GetValue(0);
    space.unit = IsUnit(unit) ? unit : std::string();
  }
  if (frameField)
  {
    const std::string frame = frameField->GetValue(0);
    space.frame = IsFrame(frame) ? frame : std::string();
  }
  return space;
}

StatedSpace ToLpsMillimetres(const std::string& path, vtkPolyData* mesh)
{
  const StatedSpace space = StatedCoordinates(path, mesh);
  const double scale = space.unit == "m" ? 1000.0 : 1.0;
  const double turn = space.frame == "RAS" ? -1.0 : 1.0; // RAS: x and y negated
  if ((scale == 1.0 && turn == 1.0) || !mesh || !mesh->GetPoints())
  {
    return space;
  }
  vtkPoints* points = mesh->GetPoints();
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    points->SetPoint(i, turn * scale * p[0], turn * scale * p[1], scale * p[2]);
  }
  points->Modified();
  if (vtkStringArray* array = StringField(mesh, UnitArrayName))
  {
    array->SetValue(0, "mm");
  }
  if (vtkStringArray* array = StringField(mesh, FrameArrayName))
  {
    array->SetValue(0, "LPS");
  }
  return space;
}

} // namespace bender
