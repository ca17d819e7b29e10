#include "ValidationText.h"

#include <charconv>
#include <cmath>
#include <system_error>

namespace bender
{
namespace io_detail
{

void SplitWords(std::string_view line, std::vector<std::string_view>& words)
{
  words.clear();
  std::size_t i = 0;
  while (i < line.size())
  {
    while (i < line.size() && IsBlank(line[i]))
    {
      ++i;
    }
    const std::size_t start = i;
    while (i < line.size() && !IsBlank(line[i]))
    {
      ++i;
    }
    if (i > start)
    {
      words.push_back(line.substr(start, i - start));
    }
  }
}

std::vector<std::string_view> Words(std::string_view line)
{
  std::vector<std::string_view> words;
  SplitWords(line, words);
  return words;
}

bool Number(std::string_view word, bool requireFinite)
{
  const char* begin = word.data();
  const char* end = word.data() + word.size();
  if (begin < end && *begin == '+')
  {
    ++begin;
  }
  double value = 0;
  const auto r = std::from_chars(begin, end, value);
  if (r.ptr != end || begin == end)
  {
    return false;
  }
  if (r.ec == std::errc::result_out_of_range)
  {
    return !requireFinite;
  }
  return r.ec == std::errc() && (!requireFinite || std::isfinite(value));
}

} // namespace io_detail
} // namespace bender
