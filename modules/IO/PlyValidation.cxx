#include "PlyValidation.h"

#include "InputValidation.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string_view>
#include <vector>

namespace bender
{
namespace io_detail
{

// What vtkPLYReader (VTK 9.1) and the vtkPLY library under it read safely, accepted as a
// whitelist; anything else is refused before the reader runs (docs/input-validation.md):
// - the header: "ply", "format ascii|binary_little_endian|binary_big_endian 1.0", "comment"
//   and "obj_info" lines, "element NAME COUNT", "property TYPE NAME" and "property list
//   COUNT_TYPE ITEM_TYPE NAME" with vtkPLY's type names, "end_header"; each line exactly its
//   words (vtkPLY reads missing words from an uninitialised array), at most 4000 bytes
//   (vtkPLY's line buffer is 4096 bytes), printable ASCII and tabs only (vtkPLY splits words
//   at spaces and tabs alone), no element or property named twice, and "vertex_index" only as
//   a property name (vtkPLY rewrites that word in place as "vertex_indices" on every line);
// - the elements: "vertex" with scalar x, y and z and no lists; "face", after "vertex", with
//   exactly one "vertex_indices" or "vertex_index" list of integers and no other list (the
//   reader reads scalars into a fixed record); any other element after both (the reader never
//   reads it, so one before them would shift what it reads);
// - the records, against the declared types: ASCII one record per line with exactly its
//   values, integers where the type is an integer, faces of 3 to 255 vertices (the reader
//   keeps a byte of the count) with indices below the vertex count; binary exactly as long as
//   the records, with the same bounds on lists and indices.

namespace
{

// vtkPLY reads lines with fgets into a 4096-byte buffer.
constexpr std::size_t MaxPlyLine = 4000;

// vtkPLYReader keeps a face's vertex count in one byte and copies it into 256 ids.
constexpr std::int64_t MaxFaceVertices = 255;

struct ScalarType
{
  int size = 0;
  bool isSigned = false;
  bool isInteger = true;
};

// vtkPLY 9.1's type names.
bool ParseType(std::string_view name, ScalarType& type)
{
  struct Known
  {
    const char* name;
    ScalarType type;
  };
  static const Known known[] = { { "char", { 1, true, true } },
    { "int8", { 1, true, true } },
    { "uchar", { 1, false, true } },
    { "uint8", { 1, false, true } },
    { "short", { 2, true, true } },
    { "int16", { 2, true, true } },
    { "ushort", { 2, false, true } },
    { "uint16", { 2, false, true } },
    { "int", { 4, true, true } },
    { "int32", { 4, true, true } },
    { "uint", { 4, false, true } },
    { "uint32", { 4, false, true } },
    { "float", { 4, true, false } },
    { "float32", { 4, true, false } },
    { "double", { 8, true, false } },
    { "float64", { 8, true, false } } };
  for (const Known& k : known)
  {
    if (name == k.name)
    {
      type = k.type;
      return true;
    }
  }
  return false;
}

// The range of an integer type.
std::int64_t MinValue(const ScalarType& type)
{
  return type.isSigned ? -(std::int64_t{ 1 } << (8 * type.size - 1)) : 0;
}

std::int64_t MaxValue(const ScalarType& type)
{
  return type.isSigned ? (std::int64_t{ 1 } << (8 * type.size - 1)) - 1
                       : (std::int64_t{ 1 } << (8 * type.size)) - 1;
}

struct Property
{
  std::string name;
  bool isList = false;
  ScalarType count; // lists only
  ScalarType item;  // the scalar, or each list item
  bool isFaceIndices = false;
};

struct Element
{
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

// Words as vtkPLY splits a line: at spaces and tabs.
std::vector<std::string_view> SplitWords(std::string_view line)
{
  std::vector<std::string_view> words;
  std::size_t at = 0;
  while (at < line.size())
  {
    while (at < line.size() && (line[at] == ' ' || line[at] == '\t'))
    {
      ++at;
    }
    const std::size_t start = at;
    while (at < line.size() && line[at] != ' ' && line[at] != '\t')
    {
      ++at;
    }
    if (at > start)
    {
      words.push_back(line.substr(start, at - start));
    }
  }
  return words;
}

// One little- or big-endian integer of 1, 2 or 4 bytes.
std::int64_t DecodeInteger(const unsigned char* p, const ScalarType& type, bool bigEndian)
{
  std::uint64_t value = 0;
  for (int b = 0; b < type.size; ++b)
  {
    const int shift = 8 * (bigEndian ? type.size - 1 - b : b);
    value |= static_cast<std::uint64_t>(p[b]) << shift;
  }
  if (type.isSigned && (value & (std::uint64_t{ 1 } << (8 * type.size - 1))))
  {
    return static_cast<std::int64_t>(value) - (std::int64_t{ 1 } << (8 * type.size));
  }
  return static_cast<std::int64_t>(value);
}

std::string Where(const Element& element, std::uint64_t record)
{
  return "element \"" + element.name + "\" record " + std::to_string(record + 1) + " of " +
    std::to_string(element.count);
}

bool ParseInteger(std::string_view token, std::int64_t& value)
{
  const char* begin = token.data();
  const char* end = token.data() + token.size();
  if (begin != end && *begin == '+')
  {
    ++begin;
  }
  const auto result = std::from_chars(begin, end, value);
  return result.ec == std::errc() && result.ptr == end && begin != end;
}

bool ParseReal(std::string_view token)
{
  const char* begin = token.data();
  const char* end = token.data() + token.size();
  if (begin != end && *begin == '+')
  {
    ++begin;
  }
  double value = 0;
  const auto result = std::from_chars(begin, end, value);
  // Overflow reads as inf, like atof: the mesh's finite check names it.
  return (result.ec == std::errc() || result.ec == std::errc::result_out_of_range) &&
    result.ptr == end && begin != end;
}

class PlyChecker
{
public:
  explicit PlyChecker(const std::string& data)
    : Data(data)
  {
  }

  bool Check(std::string& problem)
  {
    return this->ReadHeader(problem) && this->CheckElements(problem) &&
      (this->Ascii ? this->CheckAsciiBody(problem) : this->CheckBinaryBody(problem));
  }

private:
  const std::string& Data;
  std::size_t Position = 0; // first byte after the header
  std::size_t LineNumber = 0;
  bool Ascii = false;
  bool BigEndian = false;
  std::vector<Element> Elements;
  std::int64_t VertexCount = 0;

  bool ReadHeader(std::string& problem)
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
        const auto result =
          std::from_chars(count.data(), count.data() + count.size(), element.count);
        // vtkPLY keeps counts in an int.
        if (result.ec != std::errc() || result.ptr != count.data() + count.size() ||
          element.count > static_cast<std::uint64_t>(INT_MAX))
        {
          problem =
            where + "element count \"" + QuoteBytes(count) + "\" is not a number of records";
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

  bool CheckElements(std::string& problem)
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
        if (property.isList &&
          (property.name == "vertex_indices" || property.name == "vertex_index"))
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

  bool BadIndex(const Element& element, std::uint64_t r, std::int64_t index, std::string& problem)
  {
    problem = "PLY " + Where(element, r) + ": vertex index " + std::to_string(index) +
      " out of range (the file has " + std::to_string(this->VertexCount) + " vertices)";
    return false;
  }

  static std::string FaceSizeProblem(std::int64_t count)
  {
    return "a face of " + std::to_string(count) + " vertices (3 to " +
      std::to_string(MaxFaceVertices) + " are read)";
  }

  bool CheckAsciiBody(std::string& problem)
  {
    const std::string& data = this->Data;
    // vtkPLY reads one record per line, with fgets into a 4096-byte buffer, and splits it at
    // spaces and tabs: a record split over two lines, two records on one line, a longer line
    // or another control byte (vtkPLY would see other words) crash it. A NUL byte ends fgets'
    // string early and made vtkPLYReader free a face's list twice (found by fuzz_mesh_ply).
    std::size_t lineStart = this->Position;
    std::size_t bodyLine = this->LineNumber;
    std::string_view line;
    std::vector<std::string_view> words;
    std::string lineError;
    auto nextLine = [&]()
    {
      if (lineStart >= data.size())
      {
        return false;
      }
      std::size_t end = data.find('\n', lineStart);
      if (end == std::string::npos)
      {
        end = data.size();
      }
      line = std::string_view(data).substr(lineStart, end - lineStart);
      lineStart = end + 1;
      ++bodyLine;
      lineError.clear();
      if (line.size() >= MaxPlyLine)
      {
        lineError = "line longer than " + std::to_string(MaxPlyLine) + " bytes";
        return true;
      }
      // A carriage return ends the line for vtkPLY.
      if (const std::size_t cr = line.find('\r'); cr != std::string_view::npos)
      {
        if (line.find_first_not_of(" \t\r", cr) != std::string_view::npos)
        {
          lineError = "carriage return inside the line";
          return true;
        }
        line = line.substr(0, cr);
      }
      for (std::size_t i = 0; i < line.size(); ++i)
      {
        const auto u = static_cast<unsigned char>(line[i]);
        if ((u < 32 && line[i] != '\t') || u >= 127)
        {
          lineError = (u == 0 ? "NUL byte" : "control or non-ASCII byte") +
            std::string(" at offset ") +
            std::to_string(static_cast<std::size_t>(line.data() - data.data()) + i);
          return true;
        }
      }
      words = SplitWords(line);
      return true;
    };
    auto lineProblem = [&](const Element& element, std::uint64_t r, const std::string& what)
    {
      // The last line of the file cut short: a truncated file.
      if (what.find("ends early") != std::string::npos && lineStart >= data.size())
      {
        problem = "truncated ASCII PLY (" + Where(element, r) + " is incomplete)";
        return false;
      }
      problem = "malformed ASCII PLY line " + std::to_string(bodyLine) + " (" + Where(element, r) +
        ": " + what + ")";
      return false;
    };
    for (const Element& element : this->Elements)
    {
      for (std::uint64_t r = 0; r < element.count; ++r)
      {
        if (!nextLine())
        {
          problem = "truncated ASCII PLY (" + Where(element, r) + " is missing)";
          return false;
        }
        if (!lineError.empty())
        {
          if (lineError.rfind("NUL byte", 0) == 0)
          {
            problem = "ASCII PLY data holds a " + lineError;
            return false;
          }
          return lineProblem(element, r, lineError);
        }
        std::size_t w = 0;
        auto value = [&](std::string_view& token)
        {
          if (w >= words.size())
          {
            return false;
          }
          token = words[w++];
          return true;
        };
        std::string_view token;
        for (const Property& property : element.properties)
        {
          if (!value(token))
          {
            if (lineStart >= data.size())
            {
              problem = "truncated ASCII PLY (" + Where(element, r) + " is incomplete)";
              return false;
            }
            return lineProblem(element, r, "the record ends early (one record per line)");
          }
          std::int64_t count = 1;
          if (property.isList)
          {
            if (!ParseInteger(token, count) || count < 0 || count > MaxValue(property.count))
            {
              return lineProblem(element, r, "bad list length \"" + QuoteBytes(token) + "\"");
            }
            if (property.isFaceIndices && (count < 3 || count > MaxFaceVertices))
            {
              return lineProblem(element, r, FaceSizeProblem(count));
            }
          }
          for (std::int64_t k = 0; k < count; ++k)
          {
            // A scalar's value is the token read above; a list's items follow its length.
            if (property.isList && !value(token))
            {
              return lineProblem(element, r, "the list ends early (one record per line)");
            }
            if (property.item.isInteger)
            {
              std::int64_t number = 0;
              if (!ParseInteger(token, number))
              {
                return lineProblem(element, r, "\"" + QuoteBytes(token) + "\" is not an integer");
              }
              if (property.isFaceIndices)
              {
                if (number < 0 || number >= this->VertexCount)
                {
                  return this->BadIndex(element, r, number, problem);
                }
              }
              else if (number < MinValue(property.item) || number > MaxValue(property.item))
              {
                return lineProblem(element,
                  r,
                  "\"" + QuoteBytes(token) + "\" is out of range for \"" + property.name + "\"");
              }
            }
            else if (!ParseReal(token))
            {
              return lineProblem(element, r, "\"" + QuoteBytes(token) + "\" is not a number");
            }
          }
        }
        if (w != words.size())
        {
          return lineProblem(element, r, "more values than the record has (one record per line)");
        }
      }
    }
    // After the records: blank lines at most.
    while (nextLine())
    {
      if (!lineError.empty() || !words.empty())
      {
        problem =
          "malformed ASCII PLY line " + std::to_string(bodyLine) + " (data after the last record)";
        return false;
      }
    }
    return true;
  }

  bool CheckBinaryBody(std::string& problem)
  {
    const auto* bytes = reinterpret_cast<const unsigned char*>(this->Data.data());
    const std::uint64_t size = this->Data.size();
    std::uint64_t at = this->Position;
    for (const Element& element : this->Elements)
    {
      const bool fixed = std::none_of(element.properties.begin(),
        element.properties.end(),
        [](const Property& p) { return p.isList; });
      if (fixed)
      {
        std::uint64_t recordSize = 0;
        for (const Property& property : element.properties)
        {
          recordSize += static_cast<std::uint64_t>(property.item.size);
        }
        // Counts are below 2^31 and records at most 8 * properties bytes: no overflow.
        if (at + element.count * recordSize > size)
        {
          problem = "truncated binary PLY (element \"" + element.name + "\" announces " +
            std::to_string(element.count) + " records, the file holds " +
            std::to_string((size - std::min(at, size)) / recordSize) + ")";
          return false;
        }
        at += element.count * recordSize;
        continue;
      }
      for (std::uint64_t r = 0; r < element.count; ++r)
      {
        for (const Property& property : element.properties)
        {
          if (!property.isList)
          {
            at += static_cast<std::uint64_t>(property.item.size);
            if (at > size)
            {
              break;
            }
            continue;
          }
          const auto countSize = static_cast<std::uint64_t>(property.count.size);
          if (at + countSize > size)
          {
            at = size + 1;
            break;
          }
          const std::int64_t count = DecodeInteger(bytes + at, property.count, this->BigEndian);
          at += countSize;
          if (count < 0)
          {
            problem = "malformed binary PLY (" + Where(element, r) + ": negative list length)";
            return false;
          }
          if (property.isFaceIndices && (count < 3 || count > MaxFaceVertices))
          {
            problem =
              "malformed binary PLY (" + Where(element, r) + ": " + FaceSizeProblem(count) + ")";
            return false;
          }
          const std::uint64_t listBytes =
            static_cast<std::uint64_t>(count) * static_cast<std::uint64_t>(property.item.size);
          if (at + listBytes > size)
          {
            at = size + 1;
            break;
          }
          if (property.isFaceIndices)
          {
            for (std::int64_t k = 0; k < count; ++k)
            {
              const std::int64_t index =
                DecodeInteger(bytes + at + static_cast<std::uint64_t>(k) * property.item.size,
                  property.item,
                  this->BigEndian);
              if (index < 0 || index >= this->VertexCount)
              {
                return this->BadIndex(element, r, index, problem);
              }
            }
          }
          at += listBytes;
        }
        if (at > size)
        {
          problem =
            "truncated binary PLY (" + Where(element, r) + " ends past the end of the file)";
          return false;
        }
      }
    }
    if (at != size)
    {
      problem = "binary PLY with " + std::to_string(size - at) +
        " bytes after the last record (the header announces fewer records)";
      return false;
    }
    return true;
  }
};

bool CheckPlyBytesUnescaped(const std::string& data, std::string& problem)
{
  PlyChecker checker(data);
  return checker.Check(problem);
}

} // namespace

bool CheckPlyStructure(const std::string& path, std::string& problem)
{
  std::string data;
  {
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
      problem = "cannot be opened for reading";
      return false;
    }
    data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  return CheckPlyBytes(data, problem);
}

bool CheckPlyBytes(const std::string& data, std::string& problem)
{
  // Names in the problem come from the file: escape whatever is not printable.
  if (CheckPlyBytesUnescaped(data, problem))
  {
    return true;
  }
  problem = QuoteBytes(problem, 400);
  return false;
}

} // namespace io_detail
} // namespace bender
