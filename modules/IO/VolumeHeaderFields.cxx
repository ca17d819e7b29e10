#include "VolumeHeaderFields.h"

#include "StringUtil.h"
#include "ValidationText.h"

#include <charconv>

namespace bender
{
namespace io_detail
{

bool PositiveList(std::string_view text, std::vector<std::uint64_t>& values)
{
  values.clear();
  text = Trim(text);
  while (!text.empty())
  {
    std::size_t end = 0;
    while (end < text.size() && !IsBlank(text[end]))
    {
      ++end;
    }
    std::uint64_t v = 0;
    const auto r = std::from_chars(text.data(), text.data() + end, v);
    if (r.ec != std::errc() || r.ptr != text.data() + end || v == 0 || v > (1ull << 32) ||
      values.size() > 16)
    {
      return false;
    }
    values.push_back(v);
    text = Trim(text.substr(end));
  }
  return !values.empty();
}

bool Product(const std::vector<std::uint64_t>& sizes, std::uint64_t channels, std::uint64_t& n)
{
  long double p = static_cast<long double>(channels);
  for (const std::uint64_t s : sizes)
  {
    p *= static_cast<long double>(s);
  }
  if (p > 1e18L)
  {
    return false;
  }
  n = static_cast<std::uint64_t>(p);
  return true;
}

bool HeaderLines(std::string_view header,
  std::vector<std::string_view>& lines,
  std::string& problem)
{
  std::size_t pos = 0;
  while (pos < header.size())
  {
    std::size_t end = header.find('\n', pos);
    if (end == std::string_view::npos)
    {
      end = header.size();
    }
    std::string_view line = header.substr(pos, end - pos);
    if (line.size() > MaxHeaderLine)
    {
      problem = "header line " + std::to_string(lines.size() + 1) + " is longer than " +
        std::to_string(MaxHeaderLine) + " bytes";
      return false;
    }
    if (line.find('\0') != std::string_view::npos)
    {
      problem = "NUL byte in header line " + std::to_string(lines.size() + 1);
      return false;
    }
    if (!line.empty() && line.back() == '\r')
    {
      line.remove_suffix(1);
    }
    lines.push_back(line);
    pos = end + 1;
  }
  return true;
}

std::uint32_t Read32(const unsigned char* p, bool swap)
{
  return swap
    ? (std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | p[3])
    : (std::uint32_t(p[3]) << 24 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[1]) << 8 | p[0]);
}

std::int16_t Read16(const unsigned char* p, bool swap)
{
  return static_cast<std::int16_t>(swap ? (p[0] << 8 | p[1]) : (p[1] << 8 | p[0]));
}

} // namespace io_detail
} // namespace bender
