#include "PlyValidation.h"

#include "InputValidation.h"
#include "PlyChecker.h"

#include <charconv>
#include <fstream>
#include <iterator>
#include <string_view>
#include <vector>

namespace bender
{
namespace io_detail
{
namespace ply
{

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

std::int64_t MinValue(const ScalarType& type)
{
  return type.isSigned ? -(std::int64_t{ 1 } << (8 * type.size - 1)) : 0;
}

std::int64_t MaxValue(const ScalarType& type)
{
  return type.isSigned ? (std::int64_t{ 1 } << (8 * type.size - 1)) - 1
                       : (std::int64_t{ 1 } << (8 * type.size)) - 1;
}

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

} // namespace ply

namespace
{
bool CheckPlyBytesUnescaped(const std::string& data, std::string& problem)
{
  ply::PlyChecker checker(data);
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
