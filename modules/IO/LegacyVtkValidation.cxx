// CheckLegacyVtk: legacy VTK polydata walked section by section with the counts it announces.

#include "InputValidation.h"

#include "LegacyVtkScanner.h"
#include "StringUtil.h"
#include "ValidationText.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

namespace bender
{
namespace io_detail
{

namespace
{

bool CheckAttributes(LegacyScanner& s, std::uint64_t n, const char* section);

bool CheckFieldArrays(LegacyScanner& s, std::uint64_t expectedTuples, bool dataset)
{
  std::string_view name;
  std::uint64_t arrays = 0;
  if (!s.Word(name) || !s.Count(arrays, "FIELD array count"))
  {
    return s.Fail(s.At() + "malformed FIELD line");
  }
  if (arrays > 100000)
  {
    return s.Fail(s.At() + "FIELD with " + std::to_string(arrays) + " arrays");
  }
  for (std::uint64_t a = 0; a < arrays; ++a)
  {
    std::string_view arrayName;
    if (!s.Word(arrayName))
    {
      return s.Fail("truncated FIELD (array " + std::to_string(a + 1) + " of " +
        std::to_string(arrays) + " is missing)");
    }
    if (ToLower(arrayName) == "null_array")
    {
      continue;
    }
    std::uint64_t components = 0, tuples = 0;
    std::string_view type;
    if (!s.Count(components, "component count") || !s.Count(tuples, "tuple count") || !s.Word(type))
    {
      return s.Fail(s.At() + "malformed FIELD array line");
    }
    if (components == 0 || components > 1024)
    {
      return s.Fail(s.At() + "FIELD array with " + std::to_string(components) + " components");
    }
    if (!dataset && tuples != expectedTuples)
    {
      return s.Fail(s.At() + "FIELD array of " + std::to_string(tuples) + " tuples, expected " +
        std::to_string(expectedTuples));
    }
    // Bender's labels carry their patch names and roles as string arrays (PatchLabels.h).
    const bool strings = ToLower(type) == "string";
    if (!(strings ? s.Strings(components * tuples, "FIELD array")
                  : s.Values(components * tuples, std::string(type), "FIELD array")) ||
      !s.SkipMetadata())
    {
      return false;
    }
  }
  return true;
}

bool CheckAttributes(LegacyScanner& s, std::uint64_t n, const char* section)
{
  while (true)
  {
    const std::size_t save = s.Pos;
    std::string_view word;
    if (!s.Word(word))
    {
      return s.Problem.empty();
    }
    const std::string keyword = ToLower(word);
    std::string_view name, type;
    if (keyword == "scalars")
    {
      std::uint64_t components = 1;
      if (!s.Word(name) || !s.Word(type))
      {
        return s.Fail(s.At() + "malformed SCALARS line");
      }
      // Optional component count on the same line.
      std::size_t probe = s.Pos;
      while (probe < s.Data.size() && (s.Data[probe] == ' ' || s.Data[probe] == '\t'))
      {
        ++probe;
      }
      if (probe < s.Data.size() && std::isdigit(static_cast<unsigned char>(s.Data[probe])))
      {
        if (!s.Count(components, "component count"))
        {
          return false;
        }
      }
      if (components == 0 || components > 4)
      {
        return s.Fail(
          s.At() + "SCALARS with " + std::to_string(components) + " components (1 to 4)");
      }
      // Optional "LOOKUP_TABLE name" line.
      const std::size_t beforeTable = s.Pos;
      std::string_view table;
      if (s.Word(table) && ToLower(table) == "lookup_table")
      {
        std::string_view tableName;
        if (!s.Word(tableName))
        {
          return s.Fail(s.At() + "malformed LOOKUP_TABLE line");
        }
      }
      else
      {
        s.Pos = beforeTable;
        s.Problem.clear();
      }
      if (!s.Values(n * components, std::string(type), "SCALARS") || !s.SkipMetadata())
      {
        return false;
      }
    }
    else if (keyword == "color_scalars")
    {
      std::uint64_t components = 0;
      if (!s.Word(name) || !s.Count(components, "component count") || components == 0 ||
        components > 4)
      {
        return s.Fail(s.At() + "malformed COLOR_SCALARS line");
      }
      if (!s.Values(n * components, s.Binary ? "unsigned_char" : "float", "COLOR_SCALARS"))
      {
        return false;
      }
    }
    else if (keyword == "lookup_table")
    {
      std::uint64_t size = 0;
      if (!s.Word(name) || !s.Count(size, "table size"))
      {
        return s.Fail(s.At() + "malformed LOOKUP_TABLE line");
      }
      if (!s.Values(size * 4, s.Binary ? "unsigned_char" : "float", "LOOKUP_TABLE"))
      {
        return false;
      }
    }
    else if (keyword == "vectors" || keyword == "normals" || keyword == "tensors" ||
      keyword == "tensors6" || keyword == "global_ids" || keyword == "pedigree_ids")
    {
      if (!s.Word(name) || !s.Word(type))
      {
        return s.Fail(s.At() + "malformed " + keyword + " line");
      }
      const std::uint64_t components = keyword == "tensors"      ? 9
        : keyword == "tensors6"                                  ? 6
        : (keyword == "global_ids" || keyword == "pedigree_ids") ? 1
                                                                 : 3;
      if (!s.Values(n * components, std::string(type), section) || !s.SkipMetadata())
      {
        return false;
      }
    }
    else if (keyword == "texture_coordinates")
    {
      std::uint64_t dimension = 0;
      if (!s.Word(name) || !s.Count(dimension, "dimension") || !s.Word(type) || dimension == 0 ||
        dimension > 3)
      {
        return s.Fail(s.At() + "malformed TEXTURE_COORDINATES line");
      }
      if (!s.Values(n * dimension, std::string(type), "TEXTURE_COORDINATES") || !s.SkipMetadata())
      {
        return false;
      }
    }
    else if (keyword == "field")
    {
      if (!CheckFieldArrays(s, n, false))
      {
        return false;
      }
    }
    else
    {
      s.Pos = save; // POINT_DATA / CELL_DATA or an unknown keyword: the caller decides
      return true;
    }
  }
}

} // namespace

bool CheckLegacyVtk(std::string_view data, std::string& problem)
{
  LegacyScanner s;
  s.Data = data;
  auto line = [&](std::string& text)
  {
    const std::size_t end = data.find('\n', s.Pos);
    if (end == std::string_view::npos)
    {
      return false;
    }
    text = std::string(data.substr(s.Pos, end - s.Pos));
    s.Pos = end + 1;
    if (!text.empty() && text.back() == '\r')
    {
      text.pop_back();
    }
    return text.size() <= MaxLegacyLine;
  };
  std::string versionLine, title, encoding;
  if (!line(versionLine) || versionLine.rfind("# vtk DataFile Version ", 0) != 0)
  {
    problem = "not a legacy VTK file (the first line is not \"# vtk DataFile Version x.y\")";
    return false;
  }
  int major = -1, minor = -1;
  {
    const std::string_view v = std::string_view(versionLine).substr(23);
    const auto dot = v.find('.');
    const auto r1 =
      std::from_chars(v.data(), v.data() + (dot == std::string_view::npos ? v.size() : dot), major);
    const auto r2 = dot == std::string_view::npos
      ? std::from_chars_result{ v.data(), std::errc::invalid_argument }
      : std::from_chars(v.data() + dot + 1, v.data() + v.size(), minor);
    // Both numbers must fill their part exactly: "5|||.1" reads as 5.1 here but VTK's own
    // sscanf stops at the '|' and falls back to the pre-5.1 cell layout (found by fuzz_mesh_vtk).
    const bool whole = r1.ec == std::errc() && r2.ec == std::errc() && r1.ptr == v.data() + dot &&
      r2.ptr == v.data() + v.size();
    if (!whole || major < 1 || major > 5 || minor < 0)
    {
      problem = "not a legacy VTK file (version \"" + QuoteBytes(v) + "\" is not 1.0 to 5.1)";
      return false;
    }
  }
  if (!line(title))
  {
    problem = "legacy VTK title line missing or longer than 255 bytes";
    return false;
  }
  if (!line(encoding))
  {
    problem = "legacy VTK file without an ASCII/BINARY line";
    return false;
  }
  {
    std::string e = ToLower(encoding);
    while (!e.empty() && IsBlank(e.back()))
    {
      e.pop_back();
    }
    if (e == "binary")
    {
      s.Binary = true;
    }
    else if (e != "ascii")
    {
      problem = "legacy VTK line 3: expected ASCII or BINARY, got \"" + QuoteBytes(encoding) + "\"";
      return false;
    }
  }
  std::string_view word, kind;
  if (!s.Word(word) || ToLower(word) != "dataset" || !s.Word(kind) || ToLower(kind) != "polydata")
  {
    problem = "not a legacy VTK polydata file (no \"DATASET POLYDATA\" line)";
    return false;
  }
  const bool newCells = major >= 5;
  std::uint64_t points = 0;
  bool sawPoints = false;
  std::uint64_t cells = 0;
  while (true)
  {
    const std::size_t save = s.Pos;
    if (!s.Word(word))
    {
      if (!s.Problem.empty())
      {
        problem = s.Problem;
        return false;
      }
      break;
    }
    const std::string keyword = ToLower(word);
    if (keyword == "points")
    {
      std::string_view type;
      if (sawPoints || !s.Count(points, "point count") || !s.Word(type))
      {
        problem = s.Problem.empty() ? s.At() + "malformed POINTS line" : s.Problem;
        return false;
      }
      sawPoints = true;
      if (!s.Values(points * 3, std::string(type), "POINTS") || !s.SkipMetadata())
      {
        problem = s.Problem;
        return false;
      }
    }
    else if (keyword == "vertices" || keyword == "lines" || keyword == "polygons" ||
      keyword == "triangle_strips")
    {
      std::uint64_t first = 0, second = 0;
      if (!s.Count(first, "cell count") || !s.Count(second, "cell array size"))
      {
        problem = s.Problem;
        return false;
      }
      auto pointId = [&](std::uint64_t, std::int64_t id)
      {
        if (id < 0 || static_cast<std::uint64_t>(id) >= points)
        {
          return s.Fail(s.At() + keyword + " refers to point " + std::to_string(id) +
            ", but the file has " + std::to_string(points) + " points");
        }
        return true;
      };
      if (newCells)
      {
        // "POLYGONS nOffsets nConnectivity", then OFFSETS and CONNECTIVITY arrays.
        std::string_view offsetsWord, offsetsType, connWord, connType;
        if (!s.EndLine() || !s.Word(offsetsWord) || ToLower(offsetsWord) != "offsets" ||
          !s.Word(offsetsType))
        {
          problem = s.Problem.empty() ? s.At() + keyword + " without an OFFSETS array" : s.Problem;
          return false;
        }
        if (first == 0 && second != 0)
        {
          problem = s.At() + keyword + " with connectivity but no offsets";
          return false;
        }
        std::int64_t previous = 0;
        const std::uint64_t nOffsets = first;
        auto offset = [&](std::uint64_t i, std::int64_t value)
        {
          if ((i == 0 && value != 0) || value < previous ||
            static_cast<std::uint64_t>(value) > second ||
            (i + 1 == nOffsets && static_cast<std::uint64_t>(value) != second))
          {
            return s.Fail(s.At() + keyword + " offset " + std::to_string(i) + " is " +
              std::to_string(value) +
              (i == 0                ? " (must be 0)"
                  : value < previous ? " (offsets must not decrease)"
                  : static_cast<std::uint64_t>(value) > second
                  ? " (past the " + std::to_string(second) + " connectivity entries)"
                  : " (the last offset must equal the " + std::to_string(second) +
                    " connectivity entries)"));
          }
          previous = value;
          return true;
        };
        if (!s.Values(nOffsets, std::string(offsetsType), "OFFSETS", offset) || !s.Word(connWord) ||
          ToLower(connWord) != "connectivity" || !s.Word(connType))
        {
          problem =
            s.Problem.empty() ? s.At() + keyword + " without a CONNECTIVITY array" : s.Problem;
          return false;
        }
        if (!s.Values(second, std::string(connType), "CONNECTIVITY", pointId))
        {
          problem = s.Problem;
          return false;
        }
        cells += first > 0 ? first - 1 : 0;
      }
      else
      {
        // "POLYGONS nCells size", then size integers: for each cell, npts and npts ids.
        std::uint64_t cell = 0;
        std::uint64_t remaining = 0; // ids left in the current cell
        auto legacy = [&](std::uint64_t, std::int64_t value)
        {
          if (remaining == 0)
          {
            if (cell == first)
            {
              return s.Fail(s.At() + keyword + " holds more values than its " +
                std::to_string(first) + " cells");
            }
            if (value < 0 || static_cast<std::uint64_t>(value) > second)
            {
              return s.Fail(s.At() + keyword + " cell " + std::to_string(cell) + " has " +
                std::to_string(value) + " points");
            }
            ++cell;
            remaining = static_cast<std::uint64_t>(value);
            return true;
          }
          --remaining;
          return pointId(0, value);
        };
        if (!s.Values(second, "int", keyword.c_str(), legacy))
        {
          problem = s.Problem;
          return false;
        }
        if (cell != first || remaining != 0)
        {
          problem = keyword + ": " + std::to_string(cell) +
            " complete cells in the data, the header announces " + std::to_string(first);
          return false;
        }
        cells += first;
      }
    }
    else if (keyword == "point_data" || keyword == "cell_data")
    {
      std::uint64_t n = 0;
      if (!s.Count(n, "tuple count"))
      {
        problem = s.Problem;
        return false;
      }
      const std::uint64_t expected = keyword == "point_data" ? points : cells;
      if (n != expected)
      {
        problem = s.At() + std::string(keyword == "point_data" ? "POINT_DATA " : "CELL_DATA ") +
          std::to_string(n) + " does not match the " + std::to_string(expected) +
          (keyword == "point_data" ? " points" : " cells");
        return false;
      }
      if (!CheckAttributes(s, n, keyword.c_str()))
      {
        problem = s.Problem;
        return false;
      }
    }
    else if (keyword == "field")
    {
      if (!CheckFieldArrays(s, 0, true))
      {
        problem = s.Problem;
        return false;
      }
    }
    else if (keyword == "metadata")
    {
      s.Pos = save;
      if (!s.SkipMetadata())
      {
        problem = s.Problem;
        return false;
      }
    }
    else
    {
      s.Pos = save;
      problem = s.At() + "unknown keyword \"" + QuoteBytes(word) + "\"";
      return false;
    }
  }
  if (!sawPoints)
  {
    problem = "legacy VTK polydata without POINTS";
    return false;
  }
  return true;
}

} // namespace io_detail
} // namespace bender
