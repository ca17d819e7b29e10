#ifndef bender_LegacyVtkScanner_h
#define bender_LegacyVtkScanner_h

// Internal to CheckLegacyVtk (LegacyVtkValidation.cxx): a cursor over a legacy VTK file that
// reads its words, counts and arrays as vtkDataReader does, with every length bounded by the
// file, so that the reader is only given files it can read without overrunning a buffer.

#include "InputValidation.h"
#include "StringUtil.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>

namespace bender
{
namespace io_detail
{

/// VTK reads keyword lines and words into 256-byte buffers.
inline constexpr std::size_t MaxLegacyLine = 255;
/// The longest value of a string array accepted (Bender's patch names and roles are short).
inline constexpr std::size_t MaxLegacyString = 4096;

struct LegacyScanner
{
  std::string_view Data;
  std::size_t Pos = 0;
  bool Binary = false;
  std::string Problem;

  /// Records the first problem; always false.
  bool Fail(const std::string& what);
  std::size_t LineNumber() const;
  /// "line N: ".
  std::string At() const;

  /// The next whitespace-separated word (VTK reads words into 256-byte buffers).
  bool Word(std::string_view& word);

  /// The rest of the current line, which must be blank (VTK skips it with a 256-byte getline).
  bool EndLine();

  /// A count word: a non-negative integer up to 2^40.
  bool Count(std::uint64_t& value, const char* what);

  // n values of the given VTK type; for integer types, each value is passed to check.
  template<typename Check>
  bool Values(std::uint64_t n, const std::string& type, const char* what, Check&& check)
  {
    const std::string t = ToLower(type);
    int size = 0;
    bool integer = true;
    bool isSigned = true;
    if (t == "bit")
    {
      size = -1;
    }
    else if (t == "unsigned_char" || t == "char" || t == "signed_char")
    {
      size = 1;
      isSigned = t != "unsigned_char";
    }
    else if (t == "unsigned_short" || t == "short")
    {
      size = 2;
      isSigned = t == "short";
    }
    else if (t == "unsigned_int" || t == "int" || t == "vtktypeint32" || t == "vtktypeuint32")
    {
      size = 4;
      isSigned = t == "int" || t == "vtktypeint32";
    }
    else if (t == "unsigned_long" || t == "long" || t == "vtkidtype" || t == "vtktypeint64" ||
      t == "vtktypeuint64" || t == "unsigned_long_long" || t == "long_long")
    {
      size = 8;
      isSigned = t == "long" || t == "vtkidtype" || t == "vtktypeint64" || t == "long_long";
    }
    else if (t == "float")
    {
      size = 4;
      integer = false;
    }
    else if (t == "double")
    {
      size = 8;
      integer = false;
    }
    else
    {
      return this->Fail(
        this->At() + "unsupported data type \"" + QuoteBytes(type) + "\" for " + what);
    }
    if (this->Binary)
    {
      if (!this->EndLine())
      {
        return false;
      }
      const std::uint64_t bytes = size < 0 ? (n + 7) / 8 : n * static_cast<std::uint64_t>(size);
      if (bytes > this->Data.size() - this->Pos)
      {
        return this->Fail("truncated binary data (" + std::string(what) + " needs " +
          std::to_string(bytes) + " bytes at byte " + std::to_string(this->Pos) +
          ", the file has " + std::to_string(this->Data.size() - this->Pos) + " left)");
      }
      if (integer && size > 0)
      {
        const auto* p = reinterpret_cast<const unsigned char*>(this->Data.data() + this->Pos);
        for (std::uint64_t i = 0; i < n; ++i)
        {
          std::uint64_t raw = 0;
          for (int b = 0; b < size; ++b)
          {
            raw = (raw << 8) | p[i * size + b]; // big endian
          }
          std::int64_t value = static_cast<std::int64_t>(raw);
          if (isSigned && size < 8 && (raw >> (8 * size - 1)) != 0)
          {
            value = static_cast<std::int64_t>(raw) - (std::int64_t(1) << (8 * size));
          }
          if (!isSigned && size == 8 && (raw >> 63) != 0)
          {
            value = std::numeric_limits<std::int64_t>::max();
          }
          if (!check(i, value))
          {
            return false;
          }
        }
      }
      this->Pos += bytes;
      return true;
    }
    // ASCII: every value a number (at least two bytes each, so n is bounded by the file).
    if (n > (this->Data.size() - this->Pos) / 2 + 1)
    {
      return this->Fail("truncated data (" + std::string(what) + " announces " + std::to_string(n) +
        " values, more than the file can hold)");
    }
    for (std::uint64_t i = 0; i < n; ++i)
    {
      std::string_view word;
      if (!this->Word(word))
      {
        return this->Fail(this->Problem.empty() ? "truncated data (" + std::string(what) + ": " +
              std::to_string(i) + " of " + std::to_string(n) + " values)"
                                                : this->Problem);
      }
      if (integer)
      {
        std::int64_t value = 0;
        const char* begin = word.data();
        const char* end = word.data() + word.size();
        if (begin < end && *begin == '+')
        {
          ++begin;
        }
        const auto result = std::from_chars(begin, end, value);
        if (result.ec != std::errc() || result.ptr != end)
        {
          return this->Fail(
            this->At() + "\"" + QuoteBytes(word) + "\" is not an integer (" + what + ")");
        }
        if (!check(i, value))
        {
          return false;
        }
      }
      else
      {
        double value = 0;
        const char* begin = word.data();
        const char* end = word.data() + word.size();
        if (begin < end && *begin == '+')
        {
          ++begin;
        }
        const auto result = std::from_chars(begin, end, value);
        if ((result.ec != std::errc() && result.ec != std::errc::result_out_of_range) ||
          result.ptr != end || !std::isfinite(value))
        {
          return this->Fail(
            this->At() + "\"" + QuoteBytes(word) + "\" is not a finite number (" + what + ")");
        }
      }
    }
    return true;
  }

  bool Values(std::uint64_t n, const std::string& type, const char* what)
  {
    return this->Values(n, type, what, [](std::uint64_t, std::int64_t) { return true; });
  }

  /// n values of a string array (type "string", FIELD arrays only), after the rest of the type
  /// line: in ASCII one line per value, whose "%" escapes must be two hex digits (vtkDataReader
  /// decodes them without a bound check); in binary a big-endian length of 1, 2, 4 or 8 bytes
  /// (its two top bits say which) and the bytes. Values up to MaxLegacyString bytes, no NUL in
  /// ASCII.
  bool Strings(std::uint64_t n, const char* what);

  /// Optional "METADATA" block after an array: lines up to a blank line.
  bool SkipMetadata();
};

} // namespace io_detail
} // namespace bender

#endif
