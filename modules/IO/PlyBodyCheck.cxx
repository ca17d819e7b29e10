// The PLY records: PlyChecker::CheckAsciiBody and CheckBinaryBody.

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

bool PlyChecker::BadIndex(const Element& element,
  std::uint64_t r,
  std::int64_t index,
  std::string& problem)
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

bool PlyChecker::CheckAsciiBody(std::string& problem)
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

bool PlyChecker::CheckBinaryBody(std::string& problem)
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
        problem = "truncated binary PLY (" + Where(element, r) + " ends past the end of the file)";
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

} // namespace ply
} // namespace io_detail
} // namespace bender
