// The PLY header: PlyChecker::ReadHeader and CheckElements.

#include "PlyChecker.h"

#include "InputValidation.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstring>
#include <string_view>
#include <vector>

namespace bender
{
namespace io_detail
{
namespace ply
{

bool PlyChecker::ReadHeader(std::string& problem)
{
  std::string format;
  bool sawEnd = false;
  while (!sawEnd)
  {
    const std::size_t end = this->Data.find('\n', this->Position);
    if (end == std::string::npos)
    {
      problem = this->LineNumber == 0 ? "not a PLY file (no \"ply\" line)"
                                      : "PLY header without \"end_header\"";
      return false;
    }
    ++this->LineNumber;
    const std::string where = "PLY header line " + std::to_string(this->LineNumber) + ": ";
    if (end - this->Position >= MaxPlyLine)
    {
      problem = where + "longer than " + std::to_string(MaxPlyLine) + " bytes";
      return false;
    }
    std::string_view line =
      std::string_view(this->Data).substr(this->Position, end - this->Position);
    this->Position = end + 1;
    if (!line.empty() && line.back() == '\r')
    {
      line.remove_suffix(1);
    }
    // vtkPLY splits header lines at spaces and tabs only: any other control byte (a vertical
    // tab) makes it see other words than we do.
    for (const char c : line)
    {
      const auto u = static_cast<unsigned char>(c);
      if ((u < 32 && c != '\t') || u >= 127)
      {
        problem = where + "control or non-ASCII byte in the header";
        return false;
      }
    }
    const std::vector<std::string_view> words = SplitWords(line);
    if (this->LineNumber == 1)
    {
      if (words.size() != 1 || words[0] != "ply")
      {
        problem = "not a PLY file (the first line is not \"ply\")";
        return false;
      }
      continue;
    }
    if (words.empty())
    {
      // vtkPLY reads a blank header line as a line of no words and then dereferences a null
      // element (found by fuzz_mesh_ply).
      problem = where + "blank line in the header";
      return false;
    }
    const std::string_view keyword = words[0];
    if (keyword == "comment" || keyword == "obj_info")
    {
      // vtkPLY rewrites "vertex_index" as "vertex_indices" in place, past the line's end
      // when the line is long; comments are free text otherwise.
      continue;
    }
    // "vertex_index" (also inside "vertex_indices") only as the name of a property.
    for (std::size_t w = 0; w < words.size(); ++w)
    {
      const bool isName = keyword == "property" && w + 1 == words.size() &&
        (words[w] == "vertex_index" || words[w] == "vertex_indices");
      if (!isName && words[w].find("vertex_index") != std::string_view::npos)
      {
        problem = where + "\"vertex_index\" is reserved for the face's index list";
        return false;
      }
    }
    if (keyword == "format")
    {
      if (!format.empty())
      {
        problem = where + "a second \"format\" line";
        return false;
      }
      if (words.size() != 3 || words[2] != "1.0")
      {
        problem = where + "expected \"format ascii|binary_little_endian|binary_big_endian 1.0\"";
        return false;
      }
      format = std::string(words[1]);
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
      {
        problem = where + "unknown format \"" + QuoteBytes(format) + "\"";
        return false;
      }
      this->Ascii = format == "ascii";
      this->BigEndian = format == "binary_big_endian";
    }
    else if (keyword == "element")
    {
      if (format.empty())
      {
        problem = where + "element before the \"format\" line";
        return false;
      }
      if (words.size() != 3)
      {
        problem = where + "expected \"element NAME COUNT\"";
        return false;
      }
      Element element;
      element.name = std::string(words[1]);
      const std::string_view count = words[2];
      const auto result = std::from_chars(count.data(), count.data() + count.size(), element.count);
      // vtkPLY keeps counts in an int.
      if (result.ec != std::errc() || result.ptr != count.data() + count.size() ||
        element.count > static_cast<std::uint64_t>(INT_MAX))
      {
        problem = where + "element count \"" + QuoteBytes(count) + "\" is not a number of records";
        return false;
      }
      for (const Element& other : this->Elements)
      {
        if (other.name == element.name)
        {
          problem = where + "a second element \"" + QuoteBytes(element.name) + "\"";
          return false;
        }
      }
      this->Elements.push_back(element);
    }
    else if (keyword == "property")
    {
      if (this->Elements.empty())
      {
        problem = where + "property before any element";
        return false;
      }
      Element& element = this->Elements.back();
      Property property;
      if (words.size() >= 2 && words[1] == "list")
      {
        if (words.size() != 5)
        {
          problem = where + "expected \"property list COUNT_TYPE ITEM_TYPE NAME\"";
          return false;
        }
        property.isList = true;
        if (!ParseType(words[2], property.count) || !property.count.isInteger ||
          !ParseType(words[3], property.item))
        {
          problem = where + "unsupported list types \"" +
            QuoteBytes(std::string(words[2]) + " " + std::string(words[3])) + "\"";
          return false;
        }
      }
      else
      {
        if (words.size() != 3)
        {
          problem = where + "expected \"property TYPE NAME\"";
          return false;
        }
        if (!ParseType(words[1], property.item))
        {
          problem = where + "unknown property type \"" + QuoteBytes(words[1]) + "\"";
          return false;
        }
      }
      property.name = std::string(words.back());
      for (const Property& other : element.properties)
      {
        if (other.name == property.name)
        {
          problem = where + "a second property \"" + QuoteBytes(property.name) +
            "\" in element \"" + QuoteBytes(element.name) + "\"";
          return false;
        }
      }
      element.properties.push_back(property);
    }
    else if (keyword == "end_header")
    {
      if (words.size() != 1)
      {
        problem = where + "words after \"end_header\"";
        return false;
      }
      sawEnd = true;
    }
    else
    {
      problem = where + "unexpected \"" + QuoteBytes(keyword, 20) + "\"";
      return false;
    }
  }
  if (format.empty())
  {
    problem = "PLY header without a \"format\" line";
    return false;
  }
  return true;
}

bool PlyChecker::CheckElements(std::string& problem)
{
  // vtkPLY frees an invalid pointer when closing a file with an element that has no
  // properties, even one of no records (found by fuzz_mesh_ply).
  for (const Element& element : this->Elements)
  {
    if (element.properties.empty())
    {
      problem = "PLY element \"" + QuoteBytes(element.name, 40) + "\" (" +
        std::to_string(element.count) + " records) has no properties";
      return false;
    }
  }
  std::size_t vertex = this->Elements.size();
  std::size_t face = this->Elements.size();
  for (std::size_t e = 0; e < this->Elements.size(); ++e)
  {
    if (this->Elements[e].name == "vertex")
    {
      vertex = e;
    }
    else if (this->Elements[e].name == "face")
    {
      face = e;
    }
  }
  if (vertex == this->Elements.size())
  {
    problem = "PLY file without a \"vertex\" element";
    return false;
  }
  Element& vertices = this->Elements[vertex];
  this->VertexCount = static_cast<std::int64_t>(vertices.count);
  for (const char* axis : { "x", "y", "z" })
  {
    if (std::none_of(vertices.properties.begin(),
          vertices.properties.end(),
          [&](const Property& p) { return p.name == axis && !p.isList; }))
    {
      problem = "PLY vertex element without the properties x, y and z";
      return false;
    }
  }
  for (const Property& property : vertices.properties)
  {
    if (property.isList)
    {
      problem = "PLY vertex property \"" + QuoteBytes(property.name) +
        "\" is a list (vtkPLYReader reads vertices as scalars)";
      return false;
    }
  }
  if (face != this->Elements.size())
  {
    if (face < vertex)
    {
      problem = "PLY face element before the vertex element";
      return false;
    }
    int indexLists = 0;
    for (Property& property : this->Elements[face].properties)
    {
      if (property.isList && (property.name == "vertex_indices" || property.name == "vertex_index"))
      {
        property.isFaceIndices = true;
        ++indexLists;
      }
    }
    if (indexLists != 1)
    {
      problem = indexLists == 0
        ? "PLY face element without a \"vertex_indices\" list (or \"vertex_index\")"
        : "PLY face element with both \"vertex_indices\" and \"vertex_index\"";
      return false;
    }
    for (const Property& property : this->Elements[face].properties)
    {
      if (property.isFaceIndices && !property.item.isInteger)
      {
        problem = "PLY face indices of a floating-point type";
        return false;
      }
      if (!property.isFaceIndices &&
        (property.isList || property.name == "vertex_indices" || property.name == "vertex_index"))
      {
        problem = "PLY face property \"" + QuoteBytes(property.name) +
          "\" is not supported (a face holds one \"vertex_indices\" list and scalars)";
        return false;
      }
    }
  }
  // vtkPLYReader reads the vertex and face elements alone: another element before them
  // would be read as theirs.
  const std::size_t last = face == this->Elements.size() ? vertex : std::max(vertex, face);
  for (std::size_t e = 0; e < last; ++e)
  {
    if (e != vertex && e != face)
    {
      problem = "PLY element \"" + QuoteBytes(this->Elements[e].name) +
        "\" before the vertex and face elements (vtkPLYReader does not skip it)";
      return false;
    }
  }
  return true;
}

} // namespace ply
} // namespace io_detail
} // namespace bender
