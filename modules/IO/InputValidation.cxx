#include "InputValidation.h"

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

bool IsBlank(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

std::string Lower(std::string_view text)
{
  std::string lower(text);
  for (char& c : lower)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return lower;
}

bool StartsWith(std::string_view text, std::string_view prefix)
{
  return text.substr(0, prefix.size()) == prefix;
}

// Removes a "Name (0x55d0c...): " / "Name(0x...): " object prefix at the start.
std::string_view DropObjectPrefix(std::string_view line)
{
  const std::size_t open = line.find("(0x");
  if (open == std::string_view::npos || open > 60)
  {
    return line;
  }
  const std::size_t close = line.find("): ", open);
  if (close == std::string_view::npos || close > open + 24)
  {
    return line;
  }
  for (std::size_t i = 0; i < open; ++i)
  {
    const char c = line[i];
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == ':' || c == '_' || c == ' '))
    {
      return line;
    }
  }
  return line.substr(close + 3);
}

} // namespace

std::string QuoteBytes(std::string_view bytes, std::size_t maxLength)
{
  static const char* const hex = "0123456789abcdef";
  std::string quoted;
  for (const char c : bytes)
  {
    const auto u = static_cast<unsigned char>(c);
    std::string piece;
    if (u >= 32 && u < 127 && u != '\\')
    {
      piece = std::string(1, c);
    }
    else
    {
      piece = std::string("\\x") + hex[u >> 4] + hex[u & 15];
    }
    if (quoted.size() + piece.size() > maxLength)
    {
      quoted += "...";
      break;
    }
    quoted += piece;
  }
  return quoted;
}

std::string CleanMessage(std::string_view raw, std::size_t maxLength)
{
  // 1. Drop ANSI escape sequences (CSI "ESC [ ... final", and two-byte "ESC x").
  std::string text;
  text.reserve(std::min<std::size_t>(raw.size(), 4096));
  for (std::size_t i = 0; i < raw.size() && text.size() < 4096; ++i)
  {
    if (raw[i] == '\x1b')
    {
      if (i + 1 < raw.size() && raw[i + 1] == ']')
      {
        // OSC: up to BEL or ESC backslash.
        i += 2;
        while (i < raw.size() && raw[i] != '\x07' &&
          !(raw[i] == '\x1b' && i + 1 < raw.size() && raw[i + 1] == '\\'))
        {
          ++i;
        }
        if (i < raw.size() && raw[i] == '\x1b')
        {
          ++i;
        }
      }
      else if (i + 1 < raw.size() && raw[i + 1] == '[')
      {
        i += 2;
        while (i < raw.size() && !(raw[i] >= 0x40 && raw[i] <= 0x7e))
        {
          ++i;
        }
      }
      else
      {
        ++i;
      }
      continue;
    }
    text += raw[i];
  }
  // 2. Line by line: drop location lines and object prefixes.
  std::vector<std::string> kept;
  std::string innermostTeem; // teem chains go from the outermost call to the actual reason
  std::size_t start = 0;
  while (start <= text.size())
  {
    std::size_t end = text.find_first_of("\r\n", start);
    if (end == std::string::npos)
    {
      end = text.size();
    }
    std::string_view line(text.data() + start, end - start);
    start = end + 1;
    while (!line.empty() && IsBlank(line.front()))
    {
      line.remove_prefix(1);
    }
    while (!line.empty() && IsBlank(line.back()))
    {
      line.remove_suffix(1);
    }
    if (line.empty() || StartsWith(line, "ERROR: In ") || StartsWith(line, "Warning: In ") ||
      StartsWith(line, "Generic Warning: In ") || StartsWith(line, "Location: ") ||
      StartsWith(line, "File: ") || StartsWith(line, "Line: "))
    {
      continue;
    }
    for (std::string_view prefix : { "itk::ExceptionObject (",
           "itk::ERROR: ",
           "ITK ERROR: ",
           "itk::WARNING: ",
           "ITK WARNING: ",
           "ERROR: ",
           "Description: ",
           "Warning: " })
    {
      if (StartsWith(line, prefix))
      {
        line.remove_prefix(prefix.size());
      }
    }
    line = DropObjectPrefix(line);
    // teem's "[nrrd] nrrdLoad: trouble reading ..." chains: drop "[nrrd] function: ".
    std::string cleaned(line);
    bool teem = false;
    for (const char* tag : { "[nrrd] ", "[biff] ", "[air] ", "[hest] " })
    {
      teem = teem || cleaned.find(tag) != std::string::npos;
      for (std::size_t at = cleaned.find(tag); at != std::string::npos; at = cleaned.find(tag, at))
      {
        std::size_t end = at + std::strlen(tag);
        const std::size_t colon = cleaned.find(": ", end);
        if (colon != std::string::npos && colon < end + 40 &&
          cleaned.substr(end, colon - end).find(' ') == std::string::npos)
        {
          end = colon + 2;
        }
        cleaned.erase(at, end - at);
      }
    }
    if (teem)
    {
      if (!cleaned.empty())
      {
        innermostTeem = cleaned;
      }
      continue;
    }
    if (!cleaned.empty() && (kept.empty() || kept.back() != cleaned))
    {
      kept.push_back(cleaned);
    }
  }
  if (!innermostTeem.empty())
  {
    // "ReadImageInformation: Error reading FILE:" says nothing the caller does not say.
    kept.assign(1, innermostTeem);
  }
  std::string joined;
  for (const std::string& line : kept)
  {
    joined += joined.empty() ? line : "; " + line;
  }
  // 3. Escape non-printables, collapse blanks, cut.
  std::string clean;
  bool lastBlank = false;
  static const char* const hex = "0123456789abcdef";
  for (const char c : joined)
  {
    const auto u = static_cast<unsigned char>(c);
    if (c == ' ' || c == '\t')
    {
      if (!lastBlank)
      {
        clean += ' ';
      }
      lastBlank = true;
      continue;
    }
    lastBlank = false;
    if (u >= 32 && u < 127)
    {
      clean += c;
    }
    else
    {
      clean += std::string("\\x") + hex[u >> 4] + hex[u & 15];
    }
    if (clean.size() > maxLength + 8)
    {
      break;
    }
  }
  if (clean.size() > maxLength)
  {
    clean = clean.substr(0, maxLength > 3 ? maxLength - 3 : 0) + "...";
  }
  return clean.empty() ? "unknown error" : clean;
}

// ---------------------------------------------------------------------------------------------
// Legacy VTK
// ---------------------------------------------------------------------------------------------

namespace
{

constexpr std::size_t MaxLegacyLine = 255;

struct LegacyScanner
{
  std::string_view Data;
  std::size_t Pos = 0;
  bool Binary = false;
  std::string Problem;

  bool Fail(const std::string& what)
  {
    if (this->Problem.empty())
    {
      this->Problem = what;
    }
    return false;
  }

  std::size_t LineNumber() const
  {
    return 1 +
      static_cast<std::size_t>(std::count(this->Data.begin(),
        this->Data.begin() + static_cast<std::ptrdiff_t>(std::min(this->Pos, this->Data.size())),
        '\n'));
  }

  std::string At() const { return "line " + std::to_string(this->LineNumber()) + ": "; }

  // The next whitespace-separated word (VTK reads words into 256-byte buffers).
  bool Word(std::string_view& word)
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

  // The rest of the current line, which must be blank (VTK skips it with a 256-byte getline).
  bool EndLine()
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

  bool Count(std::uint64_t& value, const char* what)
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

  // n values of the given VTK type; for integer types, each value is passed to check.
  template<typename Check>
  bool Values(std::uint64_t n, const std::string& type, const char* what, Check&& check)
  {
    const std::string t = Lower(type);
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

  // Optional "METADATA" block after an array: lines up to a blank line.
  bool SkipMetadata()
  {
    const std::size_t save = this->Pos;
    std::string_view word;
    if (!this->Word(word) || Lower(word) != "metadata")
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
};

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
    if (Lower(arrayName) == "null_array")
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
    if (!s.Values(components * tuples, std::string(type), "FIELD array") || !s.SkipMetadata())
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
    const std::string keyword = Lower(word);
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
      if (s.Word(table) && Lower(table) == "lookup_table")
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
    std::string e = Lower(encoding);
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
  if (!s.Word(word) || Lower(word) != "dataset" || !s.Word(kind) || Lower(kind) != "polydata")
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
    const std::string keyword = Lower(word);
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
        if (!s.EndLine() || !s.Word(offsetsWord) || Lower(offsetsWord) != "offsets" ||
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
          Lower(connWord) != "connectivity" || !s.Word(connType))
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

// ---------------------------------------------------------------------------------------------
// ASCII STL and OBJ
// ---------------------------------------------------------------------------------------------

namespace
{

// Splits data into lines (without "\r\n"); false when one is longer than maxLine.
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

std::vector<std::string_view> Words(std::string_view line)
{
  std::vector<std::string_view> words;
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
  return words;
}

bool Number(std::string_view word, bool requireFinite = false)
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

} // namespace

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
      const std::string key = Lower(w[0]);
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
          if (key != "facet" || w.size() != 5 || Lower(w[1]) != "normal" || !Number(w[2]) ||
            !Number(w[3]) || !Number(w[4]))
          {
            return expect("\"facet normal x y z\" or \"endsolid\"");
          }
          state = 2;
          return true;
        case 2:
          if (key != "outer" || w.size() != 2 || Lower(w[1]) != "loop")
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

// ---------------------------------------------------------------------------------------------
// VTK XML
// ---------------------------------------------------------------------------------------------

namespace
{

struct XmlTag
{
  std::string Name;
  std::vector<std::pair<std::string, std::string>> Attributes;
  bool Closing = false;
  bool SelfClosing = false;

  const std::string* Get(const char* key) const
  {
    for (const auto& [k, v] : this->Attributes)
    {
      if (k == key)
      {
        return &v;
      }
    }
    return nullptr;
  }
};

// Reads the tag starting at data[pos] == '<'; pos moves past '>'.
bool ReadTag(std::string_view data, std::size_t& pos, XmlTag& tag, std::string& problem)
{
  tag = XmlTag{};
  const std::size_t end = data.find('>', pos);
  if (end == std::string_view::npos || end - pos > 65536)
  {
    problem = "truncated or malformed XML tag at byte " + std::to_string(pos);
    return false;
  }
  std::string_view body = data.substr(pos + 1, end - pos - 1);
  pos = end + 1;
  if (!body.empty() && body.front() == '/')
  {
    tag.Closing = true;
    body.remove_prefix(1);
  }
  if (!body.empty() && body.back() == '/')
  {
    tag.SelfClosing = true;
    body.remove_suffix(1);
  }
  std::size_t i = 0;
  while (i < body.size() && !IsBlank(body[i]))
  {
    ++i;
  }
  tag.Name = std::string(body.substr(0, i));
  while (i < body.size())
  {
    while (i < body.size() && IsBlank(body[i]))
    {
      ++i;
    }
    if (i >= body.size())
    {
      break;
    }
    const std::size_t eq = body.find('=', i);
    if (eq == std::string_view::npos || eq + 1 >= body.size() ||
      (body[eq + 1] != '"' && body[eq + 1] != '\''))
    {
      problem = "malformed attribute in <" + QuoteBytes(tag.Name) + ">";
      return false;
    }
    const char quote = body[eq + 1];
    const std::size_t close = body.find(quote, eq + 2);
    if (close == std::string_view::npos)
    {
      problem = "unterminated attribute in <" + QuoteBytes(tag.Name) + ">";
      return false;
    }
    std::string key(body.substr(i, eq - i));
    while (!key.empty() && IsBlank(key.back()))
    {
      key.pop_back();
    }
    tag.Attributes.emplace_back(key, std::string(body.substr(eq + 2, close - eq - 2)));
    i = close + 1;
  }
  return true;
}

bool ParseCount(const std::string& text, std::uint64_t& value)
{
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  while (begin < end && IsBlank(*begin))
  {
    ++begin;
  }
  while (end > begin && IsBlank(end[-1]))
  {
    --end;
  }
  const auto result = std::from_chars(begin, end, value);
  return result.ec == std::errc() && result.ptr == end && begin != end;
}

bool ParseExtent(const std::string& text, std::uint64_t& tuples)
{
  const char* p = text.data();
  const char* end = text.data() + text.size();
  std::array<long long, 6> e{};
  for (long long& v : e)
  {
    while (p < end && IsBlank(*p))
    {
      ++p;
    }
    const auto result = std::from_chars(p, end, v);
    if (result.ec != std::errc() || std::llabs(v) > (1ll << 31))
    {
      return false;
    }
    p = result.ptr;
  }
  long double n = 1;
  for (int a = 0; a < 3; ++a)
  {
    if (e[2 * a + 1] < e[2 * a])
    {
      return false;
    }
    n *= static_cast<long double>(e[2 * a + 1] - e[2 * a] + 1);
  }
  if (n > 1e15L)
  {
    return false;
  }
  tuples = static_cast<std::uint64_t>(n);
  return true;
}

int XmlTypeSize(const std::string& type)
{
  static const std::array<std::pair<const char*, int>, 12> types{ { { "Int8", 1 },
    { "UInt8", 1 },
    { "Int16", 2 },
    { "UInt16", 2 },
    { "Int32", 4 },
    { "UInt32", 4 },
    { "Int64", 8 },
    { "UInt64", 8 },
    { "Float32", 4 },
    { "Float64", 8 },
    { "Char", 1 },
    { "String", 1 } } };
  for (const auto& [name, size] : types)
  {
    if (type == name)
    {
      return size;
    }
  }
  return 0;
}

// The first `bytes` bytes of base64 text (blanks before it skipped), as vtkBase64InputStream
// decodes them; false when the text holds fewer or another character comes first.
bool DecodeBase64Prefix(std::string_view text, std::size_t bytes, std::string& out)
{
  out.clear();
  std::size_t i = 0;
  while (i < text.size() && IsBlank(text[i]))
  {
    ++i;
  }
  std::uint32_t buffer = 0;
  int bits = 0;
  for (; i < text.size() && out.size() < bytes; ++i)
  {
    const char c = text[i];
    std::uint32_t v = 0;
    if (c >= 'A' && c <= 'Z')
    {
      v = static_cast<std::uint32_t>(c - 'A');
    }
    else if (c >= 'a' && c <= 'z')
    {
      v = static_cast<std::uint32_t>(c - 'a' + 26);
    }
    else if (c >= '0' && c <= '9')
    {
      v = static_cast<std::uint32_t>(c - '0' + 52);
    }
    else if (c == '+' || c == '/')
    {
      v = c == '+' ? 62 : 63;
    }
    else
    {
      return false;
    }
    buffer = (buffer << 6) | v;
    bits += 6;
    if (bits >= 8)
    {
      bits -= 8;
      out.push_back(static_cast<char>((buffer >> bits) & 0xff));
    }
  }
  return out.size() == bytes;
}

// Word `index` of a decoded block header.
std::uint64_t DecodeWord(const std::string& header,
  std::uint64_t index,
  std::uint64_t word,
  bool bigEndian)
{
  std::uint64_t value = 0;
  for (std::uint64_t b = 0; b < word; ++b)
  {
    const auto byte = static_cast<unsigned char>(header[index * word + b]);
    value |= static_cast<std::uint64_t>(byte) << (8 * (bigEndian ? word - 1 - b : b));
  }
  return value;
}

// A compressed array's header ("blocks, block size, last block size, compressed sizes..."):
// vtkXMLDataParser allocates the block tables and the blocks it announces, so they must fit the
// memory budget and the bytes that follow (availableWords: header words the data could hold).
bool CheckCompressionHeader(std::uint64_t blocks,
  std::uint64_t blockSize,
  std::uint64_t lastSize,
  std::uint64_t availableWords,
  std::uint64_t budgetBytes,
  const std::string& where,
  std::string& problem)
{
  if (blocks > availableWords || blockSize > budgetBytes || lastSize > blockSize ||
    static_cast<long double>(blocks) * blockSize > static_cast<long double>(budgetBytes))
  {
    problem = "VTK XML compressed block header " + where + " announces " + std::to_string(blocks) +
      " blocks of " + std::to_string(blockSize) + " bytes (beyond the file or the memory budget)";
    return false;
  }
  return true;
}

// A compressed array's block header in base64 text (inline binary data, or a block of base64
// appended data): the three counts, then every block's compressed size, which vtkXMLDataParser
// allocates before reading (a forged one asked for 2^63 bytes; found by fuzz_mesh_vtp).
bool CheckBase64CompressionHeader(std::string_view text,
  std::uint64_t word,
  bool bigEndian,
  std::uint64_t budgetBytes,
  const std::string& where,
  std::string& problem)
{
  std::string header;
  if (!DecodeBase64Prefix(text, 3 * word, header))
  {
    problem = "VTK XML data without a valid base64 compressed block header " + where;
    return false;
  }
  const std::uint64_t blocks = DecodeWord(header, 0, word, bigEndian);
  // Every 4 characters of base64 hold 3 bytes.
  const std::uint64_t availableBytes = text.size() / 4 * 3;
  if (!CheckCompressionHeader(blocks,
        DecodeWord(header, 1, word, bigEndian),
        DecodeWord(header, 2, word, bigEndian),
        availableBytes / word,
        budgetBytes,
        where,
        problem))
  {
    return false;
  }
  if (!DecodeBase64Prefix(text, (3 + blocks) * word, header))
  {
    problem = "truncated VTK XML compressed block header " + where;
    return false;
  }
  long double compressedTotal = 0;
  for (std::uint64_t b = 0; b < blocks; ++b)
  {
    compressedTotal += static_cast<long double>(DecodeWord(header, 3 + b, word, bigEndian));
  }
  if (compressedTotal > static_cast<long double>(availableBytes))
  {
    problem = "truncated VTK XML file (compressed blocks " + where + " end past the data)";
    return false;
  }
  return true;
}

} // namespace

bool CheckVtkXml(std::string_view data,
  std::string_view expectedType,
  std::uint64_t budgetBytes,
  std::string& problem)
{
  // Truncated files lose the closing tag first.
  std::size_t last = data.size();
  while (last > 0 && (IsBlank(data[last - 1]) || data[last - 1] == '\0'))
  {
    --last;
  }
  const std::string_view closing = "</VTKFile>";
  if (last < closing.size() || data.substr(last - closing.size(), closing.size()) != closing)
  {
    problem = "truncated VTK XML file (it does not end with </VTKFile>)";
    return false;
  }
  const std::size_t appended = data.find("<AppendedData");
  const std::string_view markup = data.substr(0, appended);
  std::size_t pos = 0;
  bool sawRoot = false;
  std::string headerType = "UInt32";
  std::string byteOrder = "LittleEndian";
  bool compressed = false;
  std::uint64_t points = 0, cells = 0, extentTuples = 0, pieceCount = 0;
  std::string section;
  long double totalBytes = 0;
  std::vector<std::uint64_t> offsets;
  while (true)
  {
    pos = markup.find('<', pos);
    if (pos == std::string_view::npos)
    {
      break;
    }
    if (markup.substr(pos, 2) == "<?" || markup.substr(pos, 2) == "<!")
    {
      const std::size_t end = markup.find('>', pos);
      if (end == std::string_view::npos)
      {
        problem = "truncated XML declaration";
        return false;
      }
      pos = end + 1;
      continue;
    }
    XmlTag tag;
    if (!ReadTag(markup, pos, tag, problem))
    {
      return false;
    }
    if (tag.Closing)
    {
      continue;
    }
    if (!sawRoot)
    {
      if (tag.Name != "VTKFile")
      {
        problem = "not a VTK XML file (the root element is not <VTKFile>)";
        return false;
      }
      sawRoot = true;
      const std::string* type = tag.Get("type");
      if (!type || *type != expectedType)
      {
        problem = "not a VTK XML " + std::string(expectedType) + " file (type \"" +
          QuoteBytes(type ? *type : "") + "\")";
        return false;
      }
      const std::string* order = tag.Get("byte_order");
      if (order && *order != "LittleEndian" && *order != "BigEndian")
      {
        problem = "VTK XML file with byte_order \"" + QuoteBytes(*order) + "\"";
        return false;
      }
      if (order)
      {
        byteOrder = *order;
      }
      if (const std::string* header = tag.Get("header_type"))
      {
        if (*header != "UInt32" && *header != "UInt64")
        {
          problem = "VTK XML file with header_type \"" + QuoteBytes(*header) +
            "\" (UInt32 or UInt64 expected)";
          return false;
        }
        headerType = *header;
      }
      if (const std::string* compressor = tag.Get("compressor"))
      {
        if (*compressor != "vtkZLibDataCompressor" && *compressor != "vtkLZ4DataCompressor" &&
          *compressor != "vtkLZMADataCompressor")
        {
          problem = "VTK XML file with compressor \"" + QuoteBytes(*compressor) + "\"";
          return false;
        }
        compressed = true;
      }
      continue;
    }
    if (tag.Name == "Piece")
    {
      if (++pieceCount > 1024)
      {
        problem = "VTK XML file with more than 1024 pieces";
        return false;
      }
      points = cells = 0;
      for (const auto& [key, value] : tag.Attributes)
      {
        std::uint64_t n = 0;
        if (key.rfind("NumberOf", 0) == 0)
        {
          if (!ParseCount(value, n) || n > budgetBytes)
          {
            problem = "VTK XML Piece with " + QuoteBytes(key) + "=\"" + QuoteBytes(value) + "\"";
            return false;
          }
          if (key == "NumberOfPoints")
          {
            points = n;
          }
          else
          {
            cells = std::max(cells, n);
          }
        }
        else if (key == "Extent")
        {
          if (!ParseExtent(value, extentTuples))
          {
            problem = "VTK XML Piece with Extent \"" + QuoteBytes(value) + "\"";
            return false;
          }
          points = extentTuples;
          cells = extentTuples;
        }
      }
      continue;
    }
    if (tag.Name == "ImageData")
    {
      const std::string* whole = tag.Get("WholeExtent");
      std::uint64_t tuples = 0;
      if (!whole || !ParseExtent(*whole, tuples))
      {
        problem = "VTK XML ImageData without a valid WholeExtent";
        return false;
      }
      continue;
    }
    if (tag.Name == "PointData" || tag.Name == "CellData" || tag.Name == "Points" ||
      tag.Name == "Verts" || tag.Name == "Lines" || tag.Name == "Strips" || tag.Name == "Polys" ||
      tag.Name == "FieldData")
    {
      section = tag.Name;
      continue;
    }
    if (tag.Name == "DataArray" || tag.Name == "Array")
    {
      const std::string* type = tag.Get("type");
      const int size = type ? XmlTypeSize(*type) : 0;
      if (size == 0)
      {
        problem = "VTK XML DataArray of type \"" + QuoteBytes(type ? *type : "") + "\"";
        return false;
      }
      std::uint64_t components = 1;
      if (const std::string* c = tag.Get("NumberOfComponents"))
      {
        if (!ParseCount(*c, components) || components == 0 || components > 64)
        {
          problem = "VTK XML DataArray with NumberOfComponents=\"" + QuoteBytes(*c) +
            "\" (1 to 64 supported)";
          return false;
        }
      }
      std::uint64_t tuples = section == "Points" || section == "PointData" ? points : cells;
      if (section == "Verts" || section == "Lines" || section == "Strips" || section == "Polys")
      {
        tuples = 0; // connectivity: bounded by the file's bytes below
      }
      if (const std::string* t = tag.Get("NumberOfTuples"))
      {
        if (!ParseCount(*t, tuples))
        {
          problem = "VTK XML DataArray with NumberOfTuples=\"" + QuoteBytes(*t) + "\"";
          return false;
        }
      }
      const std::string* format = tag.Get("format");
      if (format && *format != "ascii" && *format != "binary" && *format != "appended")
      {
        problem = "VTK XML DataArray with format \"" + QuoteBytes(*format) + "\"";
        return false;
      }
      // VTK's reader takes an array with an offset attribute as appended whatever its format
      // attribute says (or when it has none: a misspelt "formAt" let an unchecked block header
      // announce a 2^61-byte block; found by fuzz_mesh_vtp).
      const std::string* offset = tag.Get("offset");
      if ((format && *format == "appended") || offset)
      {
        std::uint64_t o = 0;
        if (!offset || !ParseCount(*offset, o))
        {
          problem = "VTK XML appended DataArray without a valid offset";
          return false;
        }
        offsets.push_back(o);
      }
      // Inline binary data (base64) of a compressed file starts with the same block header as
      // an appended block: a forged one made vtkXMLDataParser allocate 8 TB (found by hand after
      // the fuzzers' seeds had no inline arrays).
      if (format && *format == "binary" && !offset && compressed && !tag.SelfClosing)
      {
        const std::size_t textEnd = std::min(markup.find('<', pos), markup.size());
        const std::string_view text = markup.substr(pos, textEnd - pos);
        const std::uint64_t word = headerType == "UInt64" ? 8 : 4;
        if (!CheckBase64CompressionHeader(text,
              word,
              byteOrder == "BigEndian",
              budgetBytes,
              "of an inline binary DataArray",
              problem))
        {
          return false;
        }
      }
      // vtkXMLUnstructuredDataReader sizes the connectivity by the cells' last offset before
      // reading it: an offset of 5e10 made it allocate 400 GB (found by fuzz_mesh_vtp). Where
      // the values are in the markup (ASCII, or uncompressed inline binary), no offset may exceed
      // the values the file could hold (one per byte).
      const std::string* name = tag.Get("Name");
      const bool cellOffsets =
        (section == "Verts" || section == "Lines" || section == "Strips" || section == "Polys") &&
        name && *name == "offsets" && !tag.SelfClosing && !offset;
      if (cellOffsets && (!format || *format == "ascii" || !compressed))
      {
        const std::size_t textEnd = std::min(markup.find('<', pos), markup.size());
        const std::string_view text = markup.substr(pos, textEnd - pos);
        long double largest = 0;
        if (!format || *format == "ascii")
        {
          std::size_t at = 0;
          while (at < text.size())
          {
            while (at < text.size() && IsBlank(text[at]))
            {
              ++at;
            }
            const std::size_t start = at;
            while (at < text.size() && !IsBlank(text[at]))
            {
              ++at;
            }
            if (at > start)
            {
              largest = std::max(largest,
                std::strtold(std::string(text.substr(start, at - start)).c_str(), nullptr));
            }
          }
        }
        else
        {
          // Base64 of a header word (the byte count) and the values.
          const std::uint64_t word = headerType == "UInt64" ? 8 : 4;
          std::string bytes;
          std::size_t chars = 0;
          while (chars < text.size() &&
            (IsBlank(text[chars]) || std::isalnum(static_cast<unsigned char>(text[chars])) ||
              text[chars] == '+' || text[chars] == '/'))
          {
            ++chars;
          }
          if (DecodeBase64Prefix(text, (chars / 4) * 3, bytes) || bytes.size() > word)
          {
            const bool bigEndian = byteOrder == "BigEndian";
            const bool isSigned = type->rfind("Int", 0) == 0;
            for (std::size_t at = word; at + static_cast<std::size_t>(size) <= bytes.size();
                 at += static_cast<std::size_t>(size))
            {
              std::uint64_t value = DecodeWord(bytes.substr(at, static_cast<std::size_t>(size)),
                0,
                static_cast<std::uint64_t>(size),
                bigEndian);
              long double v = static_cast<long double>(value);
              if (isSigned && size < 8 && (value >> (8 * size - 1)) != 0)
              {
                v = 0; // negative: VTK refuses it
              }
              else if (isSigned && size == 8)
              {
                v = static_cast<long double>(static_cast<std::int64_t>(value));
              }
              largest = std::max(largest, v);
            }
          }
        }
        if (largest > static_cast<long double>(data.size()))
        {
          problem = "VTK XML cell offsets up to " +
            std::to_string(static_cast<std::uint64_t>(std::min(largest, 1e19L))) +
            ", more connectivity than the file can hold";
          return false;
        }
      }
      totalBytes += static_cast<long double>(tuples) * components * size;
      if (totalBytes > static_cast<long double>(budgetBytes))
      {
        problem = "VTK XML arrays need more than the " + std::to_string(budgetBytes >> 20) +
          " MiB memory budget";
        return false;
      }
    }
  }
  if (!sawRoot)
  {
    problem = "not a VTK XML file (no <VTKFile> element)";
    return false;
  }
  if (!offsets.empty())
  {
    if (appended == std::string_view::npos)
    {
      problem = "VTK XML file with appended arrays but no <AppendedData>";
      return false;
    }
    std::size_t at = appended;
    XmlTag tag;
    if (!ReadTag(data, at, tag, problem))
    {
      return false;
    }
    const std::string* encoding = tag.Get("encoding");
    const std::size_t underscore = data.find('_', at);
    if (underscore == std::string_view::npos)
    {
      problem = "VTK XML <AppendedData> without its '_' marker";
      return false;
    }
    const std::uint64_t start = underscore + 1;
    const std::uint64_t end = last - closing.size();
    if (encoding && *encoding == "raw")
    {
      // Each block starts with a header of header_type words: the byte count (uncompressed),
      // or "blocks, block size, last block size, compressed sizes..." (compressed).
      // vtkXMLDataParser allocates what they say: they must fit the budget and the file.
      const std::uint64_t word = headerType == "UInt64" ? 8 : 4;
      const bool bigEndian = byteOrder == "BigEndian";
      auto readWord = [&](std::uint64_t at)
      {
        std::uint64_t value = 0;
        for (std::uint64_t b = 0; b < word; ++b)
        {
          const auto byte = static_cast<unsigned char>(data[at + b]);
          value |= static_cast<std::uint64_t>(byte) << (8 * (bigEndian ? word - 1 - b : b));
        }
        return value;
      };
      for (const std::uint64_t o : offsets)
      {
        if (o > end - start || start + o + word > end)
        {
          problem = "truncated VTK XML file (an appended block at offset " + std::to_string(o) +
            " lies past the end of the data)";
          return false;
        }
        const std::uint64_t at = start + o;
        if (!compressed)
        {
          if (readWord(at) > end - at - word)
          {
            problem = "truncated VTK XML file (an appended array at offset " + std::to_string(o) +
              " announces more bytes than the file holds)";
            return false;
          }
          continue;
        }
        if (at + 3 * word > end)
        {
          problem = "truncated VTK XML file (a compressed block header at offset " +
            std::to_string(o) + ")";
          return false;
        }
        const std::uint64_t blocks = readWord(at);
        const std::uint64_t blockSize = readWord(at + word);
        const std::uint64_t lastSize = readWord(at + 2 * word);
        if (blocks > (end - at) / word || at + (3 + blocks) * word > end ||
          blockSize > budgetBytes || lastSize > blockSize ||
          static_cast<long double>(blocks) * blockSize > static_cast<long double>(budgetBytes))
        {
          problem = "VTK XML compressed block header at offset " + std::to_string(o) +
            " announces " + std::to_string(blocks) + " blocks of " + std::to_string(blockSize) +
            " bytes (beyond the file or the memory budget)";
          return false;
        }
        long double compressedTotal = 0;
        for (std::uint64_t b = 0; b < blocks; ++b)
        {
          compressedTotal += static_cast<long double>(readWord(at + (3 + b) * word));
        }
        if (compressedTotal > static_cast<long double>(end - at - (3 + blocks) * word))
        {
          problem = "truncated VTK XML file (compressed blocks at offset " + std::to_string(o) +
            " end past the data)";
          return false;
        }
      }
    }
    else if (compressed)
    {
      // Any other encoding is read as base64 (offsets count its characters): each compressed
      // block's header is decoded and checked as the raw ones are.
      const std::uint64_t word = headerType == "UInt64" ? 8 : 4;
      for (const std::uint64_t o : offsets)
      {
        const std::string where = "at offset " + std::to_string(o);
        if (o > end - start)
        {
          problem = "truncated VTK XML file (no base64 compressed block header " + where + ")";
          return false;
        }
        if (!CheckBase64CompressionHeader(data.substr(start + o, end - start - o),
              word,
              byteOrder == "BigEndian",
              budgetBytes,
              where,
              problem))
        {
          return false;
        }
      }
    }
  }
  return true;
}

} // namespace io_detail
} // namespace bender
