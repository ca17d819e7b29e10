// LegacyScanner (LegacyVtkScanner.h): the words, counts, string arrays and METADATA blocks of
// a legacy VTK file.

#include "LegacyVtkScanner.h"

#include "ValidationText.h"

#include <algorithm>
#include <cctype>

namespace bender
{
namespace io_detail
{

bool LegacyScanner::Fail(const std::string& what)
{
  if (this->Problem.empty())
  {
    this->Problem = what;
  }
  return false;
}

std::size_t LegacyScanner::LineNumber() const
{
  return 1 +
    static_cast<std::size_t>(std::count(this->Data.begin(),
      this->Data.begin() + static_cast<std::ptrdiff_t>(std::min(this->Pos, this->Data.size())),
      '\n'));
}

std::string LegacyScanner::At() const
{
  return "line " + std::to_string(this->LineNumber()) + ": ";
}

bool LegacyScanner::Word(std::string_view& word)
{
  while (this->Pos < this->Data.size() && IsBlank(this->Data[this->Pos]))
  {
    ++this->Pos;
  }
  const std::size_t start = this->Pos;
  while (this->Pos < this->Data.size() && !IsBlank(this->Data[this->Pos]))
  {
    if (this->Data[this->Pos] == '\0')
    {
      return this->Fail(this->At() + "NUL byte in a text section");
    }
    ++this->Pos;
  }
  word = this->Data.substr(start, this->Pos - start);
  if (word.size() > MaxLegacyLine)
  {
    return this->Fail(this->At() + "a word longer than 255 bytes");
  }
  return !word.empty();
}

bool LegacyScanner::EndLine()
{
  const std::size_t start = this->Pos;
  while (this->Pos < this->Data.size() && this->Data[this->Pos] != '\n')
  {
    if (!IsBlank(this->Data[this->Pos]))
    {
      return this->Fail(this->At() + "unexpected \"" +
        QuoteBytes(this->Data.substr(this->Pos, 20)) + "\" at the end of a keyword line");
    }
    ++this->Pos;
  }
  if (this->Pos - start > MaxLegacyLine)
  {
    return this->Fail(this->At() + "line longer than 255 bytes");
  }
  if (this->Pos < this->Data.size())
  {
    ++this->Pos;
  }
  return true;
}

bool LegacyScanner::Count(std::uint64_t& value, const char* what)
{
  std::string_view word;
  if (!this->Word(word))
  {
    return this->Fail(this->At() + "missing " + what);
  }
  const auto result = std::from_chars(word.data(), word.data() + word.size(), value);
  if (result.ec != std::errc() || result.ptr != word.data() + word.size() || value > (1ull << 40))
  {
    return this->Fail(this->At() + "bad " + what + " \"" + QuoteBytes(word) + "\"");
  }
  return true;
}

bool LegacyScanner::SkipMetadata()
{
  const std::size_t save = this->Pos;
  std::string_view word;
  if (!this->Word(word) || ToLower(word) != "metadata")
  {
    this->Pos = save;
    this->Problem.clear();
    return true;
  }
  this->EndLine();
  for (int lines = 0; lines < 100000; ++lines)
  {
    const std::size_t start = this->Pos;
    const std::size_t end = this->Data.find('\n', start);
    const std::size_t stop = end == std::string_view::npos ? this->Data.size() : end;
    if (stop - start > 4096)
    {
      return this->Fail(this->At() + "METADATA line longer than 4096 bytes");
    }
    std::string_view line = this->Data.substr(start, stop - start);
    this->Pos = end == std::string_view::npos ? this->Data.size() : end + 1;
    if (std::all_of(line.begin(), line.end(), IsBlank))
    {
      return true;
    }
    if (end == std::string_view::npos)
    {
      return this->Fail("truncated METADATA block");
    }
  }
  return this->Fail("METADATA block too long");
}

bool LegacyScanner::Strings(std::uint64_t n, const char* what)
{
  if (!this->EndLine())
  {
    return false;
  }
  for (std::uint64_t i = 0; i < n; ++i)
  {
    const std::size_t left = this->Data.size() - this->Pos;
    const auto index = [&] { return std::to_string(i + 1) + " of " + std::to_string(n); };
    if (left == 0)
    {
      return this->Fail(
        "truncated data (" + std::string(what) + ": string " + index() + " is missing)");
    }
    if (this->Binary)
    {
      const auto* p = reinterpret_cast<const unsigned char*>(this->Data.data() + this->Pos);
      // The two top bits of the first byte: 3 -> 1 byte, 2 -> 2, 1 -> 4, 0 -> 8 (all 64 bits).
      const int kind = p[0] >> 6;
      const std::size_t header = kind == 3 ? 1 : kind == 2 ? 2 : kind == 1 ? 4 : 8;
      if (header > left)
      {
        return this->Fail("truncated binary data (" + std::string(what) +
          ": the length of string " + index() + " needs " + std::to_string(header) +
          " bytes, the file has " + std::to_string(left) + " left)");
      }
      std::uint64_t length = 0;
      for (std::size_t b = 0; b < header; ++b)
      {
        length = (length << 8) | p[b];
      }
      if (kind != 0)
      {
        length &= (std::uint64_t(1) << (8 * header - 2)) - 1;
      }
      if (length > MaxLegacyString || length > left - header)
      {
        return this->Fail(std::string(what) + ": string " + index() + " announces " +
          std::to_string(length) + " bytes" +
          (length > MaxLegacyString ? " (at most " + std::to_string(MaxLegacyString) + ")"
                                    : ", the file has " + std::to_string(left - header) + " left"));
      }
      this->Pos += header + static_cast<std::size_t>(length);
      continue;
    }
    // ASCII: the value is the whole line (it may be empty), up to the newline or the end.
    // Problems are reported at the value's line (Pos stays there).
    const std::size_t end = std::min(this->Data.find('\n', this->Pos), this->Data.size());
    const std::string_view value = this->Data.substr(this->Pos, end - this->Pos);
    if (value.size() > MaxLegacyString)
    {
      return this->Fail(this->At() + std::string(what) + ": string " + index() +
        " is longer than " + std::to_string(MaxLegacyString) + " bytes");
    }
    if (value.find('\0') != std::string_view::npos)
    {
      return this->Fail(this->At() + "NUL byte in a text section");
    }
    for (std::size_t k = 0; k < value.size(); ++k)
    {
      if (value[k] == '%' &&
        (k + 2 >= value.size() || !std::isxdigit(static_cast<unsigned char>(value[k + 1])) ||
          !std::isxdigit(static_cast<unsigned char>(value[k + 2]))))
      {
        return this->Fail(this->At() + std::string(what) + ": \"" + QuoteBytes(value) +
          "\" has a '%' that is not followed by two hex digits");
      }
    }
    this->Pos = std::min(end + 1, this->Data.size());
  }
  return true;
}

} // namespace io_detail
} // namespace bender
