// CheckObj: Wavefront OBJ as vtkOBJReader reads it.

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

bool CheckObj(std::string_view data, std::string& problem)
{
  std::uint64_t v = 0, vt = 0, vn = 0;
  // Pass 1: counts and vertex coordinates.
  if (!ForEachLine(data,
        8000,
        problem,
        [&](std::size_t number, std::string_view line)
        {
          const std::vector<std::string_view> w = Words(line);
          if (w.empty())
          {
            return true;
          }
          if (w[0] == "v")
          {
            if (w.size() < 4 || !Number(w[1], true) || !Number(w[2], true) || !Number(w[3], true))
            {
              problem =
                "line " + std::to_string(number) + ": expected 3 finite coordinates after \"v\"";
              return false;
            }
            ++v;
          }
          else if (w[0] == "vt")
          {
            ++vt;
          }
          else if (w[0] == "vn")
          {
            ++vn;
          }
          return true;
        }))
  {
    return false;
  }
  // Pass 2: every index of every element in range.
  return ForEachLine(data,
    8000,
    problem,
    [&](std::size_t number, std::string_view line)
    {
      const std::vector<std::string_view> w = Words(line);
      if (w.empty() || (w[0] != "f" && w[0] != "l" && w[0] != "p"))
      {
        return true;
      }
      int form = -1; // v, v/vt, v//vn, v/vt/vn: one form for the whole element
      for (std::size_t k = 1; k < w.size(); ++k)
      {
        // Split "v[/vt[/vn]]" into at most three parts; a trailing or extra '/' is malformed
        // (vtkOBJReader reads "1/" as a texture index into a file that may have none).
        std::string_view parts[3];
        std::size_t count = 0;
        std::string_view rest = w[k];
        bool malformed = false;
        while (true)
        {
          const std::size_t slash = rest.find('/');
          if (count == 3)
          {
            malformed = true;
            break;
          }
          parts[count++] = rest.substr(0, slash);
          if (slash == std::string_view::npos)
          {
            break;
          }
          rest = rest.substr(slash + 1);
        }
        malformed = malformed || parts[0].empty() || parts[count - 1].empty();
        if (malformed)
        {
          problem =
            "line " + std::to_string(number) + ": malformed element \"" + QuoteBytes(w[k]) + "\"";
          return false;
        }
        const int thisForm = static_cast<int>(count) * 2 + (parts[1].empty() ? 0 : 1);
        if (form >= 0 && thisForm != form)
        {
          problem = "line " + std::to_string(number) +
            ": element mixes index forms (v, v/vt, v//vn, v/vt/vn) at \"" + QuoteBytes(w[k]) + "\"";
          return false;
        }
        form = thisForm;
        const std::uint64_t counts[3] = { v, vt, vn };
        const char* names[3] = { "vertex", "texture coordinate", "normal" };
        for (std::size_t part = 0; part < count; ++part)
        {
          const std::string_view index = parts[part];
          if (index.empty())
          {
            continue; // "1//3": no texture coordinate
          }
          long long i = 0;
          const auto r = std::from_chars(index.data(), index.data() + index.size(), i);
          if (r.ec != std::errc() || r.ptr != index.data() + index.size() || i < 1 ||
            static_cast<std::uint64_t>(i) > counts[part])
          {
            problem = "line " + std::to_string(number) + ": " + names[part] + " index \"" +
              QuoteBytes(index) + "\" out of range (the file has " + std::to_string(counts[part]) +
              ")";
            return false;
          }
        }
      }
      return true;
    });
}

} // namespace io_detail
} // namespace bender
