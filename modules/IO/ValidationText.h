#ifndef bender_ValidationText_h
#define bender_ValidationText_h

// Internal to the pre-validators (InputValidation.h, VolumeValidation.h, OffFormat.h): the
// text scanning they share. Never throws; no library dependency (the fuzz harnesses link it).

#include <string>
#include <string_view>
#include <vector>

namespace bender
{
namespace io_detail
{

/// Space, tab, CR, LF, FF or VT.
inline bool IsBlank(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

/// Calls visit(number, line) for each line of data (numbered from 1, without its "\r\n");
/// false with problem set when a line is longer than maxLine bytes or holds a NUL byte, and
/// false when visit returns false.
template<typename Visit>
bool ForEachLine(std::string_view data, std::size_t maxLine, std::string& problem, Visit&& visit)
{
  std::size_t number = 0;
  for (std::size_t pos = 0; pos < data.size();)
  {
    std::size_t end = data.find('\n', pos);
    if (end == std::string_view::npos)
    {
      end = data.size();
    }
    std::string_view line = data.substr(pos, end - pos);
    pos = end + 1;
    ++number;
    if (line.size() > maxLine)
    {
      problem =
        "line " + std::to_string(number) + " is longer than " + std::to_string(maxLine) + " bytes";
      return false;
    }
    if (line.find('\0') != std::string_view::npos)
    {
      problem = "line " + std::to_string(number) + ": NUL byte (binary data in a text file)";
      return false;
    }
    if (!line.empty() && line.back() == '\r')
    {
      line.remove_suffix(1);
    }
    if (!visit(number, line))
    {
      return false;
    }
  }
  return true;
}

/// The blank-separated words of line, into words (cleared first: a caller scanning many lines
/// keeps one vector).
void SplitWords(std::string_view line, std::vector<std::string_view>& words);

/// The blank-separated words of line.
std::vector<std::string_view> Words(std::string_view line);

/// word is a number as the C locale reads it (a leading '+' allowed); with requireFinite, a
/// finite one (out of range or inf/nan refused).
bool Number(std::string_view word, bool requireFinite = false);

} // namespace io_detail
} // namespace bender

#endif
