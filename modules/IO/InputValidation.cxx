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

namespace
{

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

} // namespace io_detail
} // namespace bender
