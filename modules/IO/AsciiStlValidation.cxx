// CheckAsciiStl: ASCII STL as vtkSTLReader reads it.

#include "InputValidation.h"

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

bool CheckAsciiStl(std::string_view data, std::string& problem)
{
  // States: 0 outside a solid, 1 in a solid, 2 after "facet normal", 3 in a loop (count
  // vertices), 4 after "endloop".
  int state = 0;
  int vertices = 0;
  std::size_t facets = 0;
  std::string where;
  const bool ok = ForEachLine(data,
    4000,
    problem,
    [&](std::size_t number, std::string_view line)
    {
      const std::vector<std::string_view> w = Words(line);
      if (w.empty())
      {
        return true;
      }
      const std::string key = ToLower(w[0]);
      where = "ASCII STL line " + std::to_string(number) + ": ";
      auto expect = [&](const char* what)
      {
        problem = where + "expected " + what + ", got \"" + QuoteBytes(line, 40) + "\"";
        return false;
      };
      switch (state)
      {
        case 0:
          if (key != "solid")
          {
            return expect("\"solid\"");
          }
          state = 1;
          return true;
        case 1:
          if (key == "endsolid")
          {
            state = 0;
            return true;
          }
          if (key != "facet" || w.size() != 5 || ToLower(w[1]) != "normal" || !Number(w[2]) ||
            !Number(w[3]) || !Number(w[4]))
          {
            return expect("\"facet normal x y z\" or \"endsolid\"");
          }
          state = 2;
          return true;
        case 2:
          if (key != "outer" || w.size() != 2 || ToLower(w[1]) != "loop")
          {
            return expect("\"outer loop\"");
          }
          state = 3;
          vertices = 0;
          return true;
        case 3:
          if (key == "endloop" && w.size() == 1 && vertices == 3)
          {
            state = 4;
            return true;
          }
          if (key != "vertex" || w.size() != 4 || vertices == 3 || !Number(w[1]) || !Number(w[2]) ||
            !Number(w[3]))
          {
            return expect(vertices == 3 ? "\"endloop\"" : "\"vertex x y z\"");
          }
          ++vertices;
          return true;
        default:
          if (key != "endfacet" || w.size() != 1)
          {
            return expect("\"endfacet\"");
          }
          ++facets;
          state = 1;
          return true;
      }
    });
  if (!ok)
  {
    return false;
  }
  if (state != 0)
  {
    problem = "truncated ASCII STL (no \"endsolid\" after " + std::to_string(facets) + " facets)";
    return false;
  }
  return true;
}

} // namespace io_detail
} // namespace bender
