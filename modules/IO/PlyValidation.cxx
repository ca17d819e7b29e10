#include "PlyValidation.h"

#include "InputValidation.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string_view>
#include <vector>

namespace bender
{
namespace io_detail
{

namespace
{

// vtkPLY reads lines with fgets into a 4096-byte buffer.
constexpr std::size_t MaxPlyLine = 4000;

struct Property
{
  std::string name;
  bool isList = false;
  int countSize = 0; // bytes of the list count (lists only)
  int size = 0;      // bytes of the scalar, or of each list item
  bool itemSigned = false;
  bool itemInteger = true;
  bool isFaceIndices = false; // "vertex_indices" of "face": checked against the vertex count
};

struct Element
{
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

int TypeSize(const std::string& type)
{
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8")
  {
    return 1;
  }
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16")
  {
    return 2;
  }
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" ||
    type == "float32")
  {
    return 4;
  }
  if (type == "double" || type == "float64")
  {
    return 8;
  }
  return 0;
}

bool IsSignedType(const std::string& type)
{
  return type == "char" || type == "int8" || type == "short" || type == "int16" || type == "int" ||
    type == "int32";
}

bool IsIntegerType(const std::string& type)
{
  return type != "float" && type != "float32" && type != "double" && type != "float64";
}

// One little- or big-endian integer of 1, 2 or 4 bytes.
std::int64_t DecodeInteger(const unsigned char* p, int size, bool isSigned, bool bigEndian)
{
  std::uint64_t value = 0;
  for (int b = 0; b < size; ++b)
  {
    const int shift = 8 * (bigEndian ? size - 1 - b : b);
    value |= static_cast<std::uint64_t>(p[b]) << shift;
  }
  if (isSigned && (value & (std::uint64_t{ 1 } << (8 * size - 1))))
  {
    return static_cast<std::int64_t>(value) - (std::int64_t{ 1 } << (8 * size));
  }
  return static_cast<std::int64_t>(value);
}

std::string Where(const Element& element, std::uint64_t record)
{
  return "element \"" + QuoteBytes(element.name) + "\" record " + std::to_string(record + 1) +
    " of " + std::to_string(element.count);
}

// The list count of a binary record; lists never have negative lengths.
bool ReadCount(const unsigned char* p, int size, bool bigEndian, std::int64_t& count)
{
  std::uint64_t value = 0;
  for (int b = 0; b < size; ++b)
  {
    const int shift = 8 * (bigEndian ? size - 1 - b : b);
    value |= static_cast<std::uint64_t>(p[b]) << shift;
  }
  // Counts are stored signed or unsigned; a signed count with the top bit set is negative.
  const std::uint64_t topBit = std::uint64_t{ 1 } << (8 * size - 1);
  if (value & topBit)
  {
    return false;
  }
  count = static_cast<std::int64_t>(value);
  return true;
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

namespace
{
bool CheckPlyBytesUnescaped(const std::string& data, std::string& problem);
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

namespace
{
bool CheckPlyBytesUnescaped(const std::string& data, std::string& problem)
{

  // Header: text lines up to "end_header".
  std::size_t pos = 0;
  std::vector<Element> elements;
  std::string format;
  bool sawMagic = false;
  bool sawEnd = false;
  std::size_t lineNumber = 0;
  while (pos < data.size() && !sawEnd)
  {
    std::size_t end = data.find('\n', pos);
    if (end == std::string::npos)
    {
      problem = "PLY header without \"end_header\"";
      return false;
    }
    if (end - pos >= MaxPlyLine)
    {
      problem = "PLY header line " + std::to_string(lineNumber + 1) + " is longer than " +
        std::to_string(MaxPlyLine) + " bytes";
      return false;
    }
    std::string line = data.substr(pos, end - pos);
    pos = end + 1;
    ++lineNumber;
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    // vtkPLY splits header lines at spaces and tabs only: any other control byte (a vertical
    // tab) makes it see other words than a stream reader does.
    for (const char c : line)
    {
      const auto u = static_cast<unsigned char>(c);
      if ((u < 32 && c != '\t') || u >= 127)
      {
        problem = "PLY header line " + std::to_string(lineNumber) +
          ": control or non-ASCII byte in the header";
        return false;
      }
    }
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (!sawMagic)
    {
      if (keyword != "ply")
      {
        problem = "not a PLY file (no \"ply\" on the first line)";
        return false;
      }
      sawMagic = true;
      continue;
    }
    const std::string where = "PLY header line " + std::to_string(lineNumber) + ": ";
    if (keyword.empty())
    {
      // vtkPLY reads a blank header line as a line of no words and then dereferences a null
      // element (found by fuzz_mesh_ply).
      problem = where + "blank line in the header";
      return false;
    }
    if (keyword == "format")
    {
      words >> format;
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
      {
        problem = where + "unknown format \"" + QuoteBytes(format) + "\"";
        return false;
      }
    }
    else if (keyword == "element")
    {
      Element element;
      std::string count;
      words >> element.name >> count;
      const auto result = std::from_chars(count.data(), count.data() + count.size(), element.count);
      if (element.name.empty() || result.ec != std::errc() ||
        result.ptr != count.data() + count.size())
      {
        problem = where + "malformed element line";
        return false;
      }
      elements.push_back(element);
    }
    else if (keyword == "property")
    {
      if (elements.empty())
      {
        problem = where + "property before any element";
        return false;
      }
      std::string type;
      words >> type;
      Property property;
      if (type == "list")
      {
        std::string countType, itemType;
        words >> countType >> itemType;
        words >> property.name;
        property.isList = true;
        property.countSize = TypeSize(countType);
        property.size = TypeSize(itemType);
        property.itemSigned = IsSignedType(itemType);
        property.itemInteger = IsIntegerType(itemType);
        property.isFaceIndices =
          elements.back().name == "face" && property.name == "vertex_indices";
        if (property.isFaceIndices && !property.itemInteger)
        {
          problem = where + "face indices of type \"" + QuoteBytes(itemType) + "\"";
          return false;
        }
        if (property.countSize == 0 || property.countSize == 8 || property.size == 0)
        {
          problem =
            where + "unsupported list types \"" + QuoteBytes(countType + " " + itemType) + "\"";
          return false;
        }
      }
      else
      {
        words >> property.name;
        property.size = TypeSize(type);
        if (property.size == 0)
        {
          problem = where + "unknown property type \"" + QuoteBytes(type) + "\"";
          return false;
        }
      }
      elements.back().properties.push_back(property);
    }
    else if (keyword == "end_header")
    {
      sawEnd = true;
    }
    else if (keyword != "comment" && keyword != "obj_info")
    {
      problem = where + "unexpected \"" + QuoteBytes(keyword, 20) + "\"";
      return false;
    }
  }
  if (!sawEnd)
  {
    problem = "PLY header without \"end_header\"";
    return false;
  }
  if (format.empty())
  {
    problem = "PLY header without a \"format\" line";
    return false;
  }
  // vtkPLY frees an invalid pointer when closing a file with an element that has no properties,
  // even one of no records (found by fuzz_mesh_ply).
  for (const Element& element : elements)
  {
    if (element.properties.empty())
    {
      problem = "PLY element \"" + QuoteBytes(element.name, 40) + "\" (" +
        std::to_string(element.count) + " records) has no properties";
      return false;
    }
  }
  // vtkPLYReader uses face indices without checking them (a wrong one crashes it), and frees
  // an uninitialised pointer when a face element lacks "vertex_indices".
  std::int64_t vertexCount = 0;
  for (const Element& element : elements)
  {
    auto has = [&](const char* name, bool list)
    {
      for (const Property& property : element.properties)
      {
        if (property.name == name && property.isList == list)
        {
          return true;
        }
      }
      return false;
    };
    if (element.name == "vertex")
    {
      vertexCount = static_cast<std::int64_t>(element.count);
      if (!has("x", false) || !has("y", false) || !has("z", false))
      {
        problem = "PLY vertex element without the properties x, y and z";
        return false;
      }
    }
    if (element.name == "face" && element.count > 0 && !has("vertex_indices", true))
    {
      problem = "PLY face element without a \"vertex_indices\" list";
      return false;
    }
  }
  const bool hasVertices = std::any_of(
    elements.begin(), elements.end(), [](const Element& e) { return e.name == "vertex"; });
  if (!hasVertices)
  {
    problem = "PLY file without a \"vertex\" element";
    return false;
  }
  auto badIndex = [&](const Element& element, std::uint64_t r, std::int64_t index)
  {
    problem = "PLY " + Where(element, r) + ": vertex index " + std::to_string(index) +
      " out of range (the file has " + std::to_string(vertexCount) + " vertices)";
    return false;
  };

  if (format == "ascii")
  {
    // vtkPLY reads one record per line, with fgets into a 4096-byte buffer: a record split over
    // two lines, two records on one line or a longer line crash it. Check exactly that.
    // A NUL byte ends fgets' string early and made vtkPLYReader free a face's list twice
    // (found by fuzz_mesh_ply): text data has none.
    if (const std::size_t nul = data.find('\0', pos); nul != std::string::npos)
    {
      problem = "ASCII PLY data holds a NUL byte at offset " + std::to_string(nul);
      return false;
    }
    std::size_t lineStart = pos;
    std::size_t bodyLine = lineNumber;
    std::string_view line;
    const char* cursor = nullptr;
    const char* last = nullptr;
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
      cursor = line.data();
      last = line.data() + line.size();
      return true;
    };
    auto nextToken = [&](std::string_view& token)
    {
      while (cursor < last && std::strchr(" \t\r\f\v", *cursor) && *cursor != '\0')
      {
        ++cursor;
      }
      const char* start = cursor;
      while (cursor < last && !std::strchr(" \t\r\f\v", *cursor))
      {
        ++cursor;
      }
      token = std::string_view(start, static_cast<std::size_t>(cursor - start));
      return !token.empty();
    };
    auto lineProblem = [&](const Element& element, std::uint64_t r, const std::string& what)
    {
      if (what.find("ends early") != std::string::npos && lineStart >= data.size())
      {
        problem = "truncated ASCII PLY (" + Where(element, r) + " is incomplete)";
        return false;
      }
      problem = "malformed ASCII PLY line " + std::to_string(bodyLine) + " (" + Where(element, r) +
        ": " + what + ")";
      return false;
    };
    std::string_view token;
    for (const Element& element : elements)
    {
      if (element.properties.empty())
      {
        continue;
      }
      for (std::uint64_t r = 0; r < element.count; ++r)
      {
        if (!nextLine())
        {
          problem = "truncated ASCII PLY (" + Where(element, r) + " is missing)";
          return false;
        }
        if (line.size() >= MaxPlyLine)
        {
          return lineProblem(
            element, r, "line longer than " + std::to_string(MaxPlyLine) + " bytes");
        }
        for (const Property& property : element.properties)
        {
          if (!nextToken(token))
          {
            return lineProblem(element, r, "the record ends early (one record per line)");
          }
          if (property.isList)
          {
            long long count = -1;
            const auto result = std::from_chars(token.data(), token.data() + token.size(), count);
            if (result.ec != std::errc() || result.ptr != token.data() + token.size() || count < 0)
            {
              return lineProblem(element, r, "bad list length");
            }
            for (long long k = 0; k < count; ++k)
            {
              if (!nextToken(token))
              {
                return lineProblem(element, r, "the list ends early (one record per line)");
              }
              if (property.isFaceIndices)
              {
                long long index = -1;
                const auto parsed =
                  std::from_chars(token.data(), token.data() + token.size(), index);
                if (parsed.ec != std::errc() || parsed.ptr != token.data() + token.size())
                {
                  return lineProblem(element, r, "bad vertex index");
                }
                if (index < 0 || index >= vertexCount)
                {
                  return badIndex(element, r, index);
                }
              }
            }
          }
          else
          {
            double value = 0;
            const char* begin = token.data();
            if (*begin == '+')
            {
              ++begin;
            }
            const auto parsed = std::from_chars(begin, token.data() + token.size(), value);
            if ((parsed.ec != std::errc() && parsed.ec != std::errc::result_out_of_range) ||
              parsed.ptr != token.data() + token.size())
            {
              return lineProblem(element, r, "\"" + QuoteBytes(token) + "\" is not a number");
            }
          }
        }
        if (nextToken(token))
        {
          return lineProblem(element, r, "more values than the record has (one record per line)");
        }
      }
    }
    return true;
  }

  const bool bigEndian = format == "binary_big_endian";
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  const std::uint64_t size = data.size();
  std::uint64_t at = pos;
  for (const Element& element : elements)
  {
    if (element.properties.empty())
    {
      continue;
    }
    bool fixed = true;
    std::uint64_t recordSize = 0;
    for (const Property& property : element.properties)
    {
      fixed = fixed && !property.isList;
      recordSize += static_cast<std::uint64_t>(property.size);
    }
    if (fixed)
    {
      // Compare in long double: count * recordSize may overflow 64 bits for a forged count.
      if (static_cast<long double>(at) + static_cast<long double>(element.count) * recordSize >
        static_cast<long double>(size))
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
          at += static_cast<std::uint64_t>(property.size);
        }
        else
        {
          if (at + static_cast<std::uint64_t>(property.countSize) > size)
          {
            at = size + 1;
            break;
          }
          std::int64_t count = 0;
          if (!ReadCount(bytes + at, property.countSize, bigEndian, count))
          {
            problem = "malformed binary PLY (" + Where(element, r) + ": negative list length)";
            return false;
          }
          at += static_cast<std::uint64_t>(property.countSize);
          const std::uint64_t listBytes =
            static_cast<std::uint64_t>(count) * static_cast<std::uint64_t>(property.size);
          if (property.isFaceIndices && at + listBytes <= size)
          {
            for (std::int64_t k = 0; k < count; ++k)
            {
              const std::int64_t index = DecodeInteger(
                bytes + at + k * property.size, property.size, property.itemSigned, bigEndian);
              if (index < 0 || index >= vertexCount)
              {
                return badIndex(element, r, index);
              }
            }
          }
          at += listBytes;
        }
        if (at > size)
        {
          break;
        }
      }
      if (at > size)
      {
        problem = "truncated binary PLY (" + Where(element, r) + " ends past the end of the file)";
        return false;
      }
    }
  }
  return true;
}
} // namespace

} // namespace io_detail
} // namespace bender
