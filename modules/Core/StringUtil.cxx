#include "StringUtil.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

namespace bender
{

namespace
{
char LowerAscii(char c)
{
  return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
}
} // namespace

std::string ToLower(std::string_view text)
{
  std::string out(text);
  for (char& c : out)
  {
    c = LowerAscii(c);
  }
  return out;
}

bool EqualsIgnoreCase(std::string_view text, std::string_view other)
{
  if (text.size() != other.size())
  {
    return false;
  }
  for (std::size_t i = 0; i < text.size(); ++i)
  {
    if (LowerAscii(text[i]) != LowerAscii(other[i]))
    {
      return false;
    }
  }
  return true;
}

bool StartsWith(std::string_view text, std::string_view prefix)
{
  return text.size() >= prefix.size() && text.substr(0, prefix.size()) == prefix;
}

bool EndsWith(std::string_view text, std::string_view suffix)
{
  return text.size() >= suffix.size() && text.substr(text.size() - suffix.size()) == suffix;
}

std::string LowerExtension(const std::string& path)
{
  return ToLower(std::filesystem::path(path).extension().string());
}

std::string LowerDoubleExtension(const std::string& path)
{
  const std::filesystem::path p(path);
  const std::string last = ToLower(p.extension().string());
  if (last == ".gz" || last == ".bz2" || last == ".xz" || last == ".zst")
  {
    const std::string inner = ToLower(p.stem().extension().string());
    return inner + last;
  }
  return last;
}

std::string DisplayName(const std::string& path)
{
  const std::string name = std::filesystem::path(path).filename().string();
  return name.empty() ? path : name;
}

std::string FormatPoint(const std::array<double, 3>& p)
{
  // A coordinate a millionth of the point's size is zero (no "1.041e-17" in a message).
  const double size = std::max({ std::abs(p[0]), std::abs(p[1]), std::abs(p[2]) });
  auto shown = [size](double v) { return std::abs(v) <= 1e-6 * size ? 0.0 : v; };
  std::ostringstream s;
  s.precision(4);
  s << "(" << shown(p[0]) << ", " << shown(p[1]) << ", " << shown(p[2]) << ")";
  return s.str();
}

std::string FormatNumber(double value, int digits)
{
  std::ostringstream s;
  s.precision(digits);
  s << value;
  return s.str();
}

std::string CountOf(std::size_t count, std::string_view noun)
{
  return std::to_string(count) + " " + std::string(noun) + (count == 1 ? "" : "s");
}

std::string_view Trim(std::string_view text)
{
  const char* blanks = " \t\r\n\f\v";
  const std::size_t first = text.find_first_not_of(blanks);
  if (first == std::string_view::npos)
  {
    return {};
  }
  const std::size_t last = text.find_last_not_of(blanks);
  return text.substr(first, last - first + 1);
}

} // namespace bender
