// CheckVtkXml: VTK XML files (.vtp, .vti) as vtkXMLReader reads them.

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

struct XmlTag
{
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  bool closing = false;
  bool selfClosing = false;

  const std::string* Get(const char* key) const
  {
    for (const auto& [k, v] : this->attributes)
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
    tag.closing = true;
    body.remove_prefix(1);
  }
  if (!body.empty() && body.back() == '/')
  {
    tag.selfClosing = true;
    body.remove_suffix(1);
  }
  std::size_t i = 0;
  while (i < body.size() && !IsBlank(body[i]))
  {
    ++i;
  }
  tag.name = std::string(body.substr(0, i));
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
      problem = "malformed attribute in <" + QuoteBytes(tag.name) + ">";
      return false;
    }
    const char quote = body[eq + 1];
    const std::size_t close = body.find(quote, eq + 2);
    if (close == std::string_view::npos)
    {
      problem = "unterminated attribute in <" + QuoteBytes(tag.name) + ">";
      return false;
    }
    std::string key(body.substr(i, eq - i));
    while (!key.empty() && IsBlank(key.back()))
    {
      key.pop_back();
    }
    tag.attributes.emplace_back(key, std::string(body.substr(eq + 2, close - eq - 2)));
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
    if (tag.closing)
    {
      continue;
    }
    if (!sawRoot)
    {
      if (tag.name != "VTKFile")
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
    if (tag.name == "Piece")
    {
      if (++pieceCount > 1024)
      {
        problem = "VTK XML file with more than 1024 pieces";
        return false;
      }
      points = cells = 0;
      for (const auto& [key, value] : tag.attributes)
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
    if (tag.name == "ImageData")
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
    if (tag.name == "PointData" || tag.name == "CellData" || tag.name == "Points" ||
      tag.name == "Verts" || tag.name == "Lines" || tag.name == "Strips" || tag.name == "Polys" ||
      tag.name == "FieldData")
    {
      section = tag.name;
      continue;
    }
    if (tag.name == "DataArray" || tag.name == "Array")
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
      if (format && *format == "binary" && !offset && compressed && !tag.selfClosing)
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
        name && *name == "offsets" && !tag.selfClosing && !offset;
      if (cellOffsets && (!format || *format == "ascii" || !compressed))
      {
        const std::size_t textEnd = std::min(markup.find('<', pos), markup.size());
        const std::string_view text = markup.substr(pos, textEnd - pos);
        long double largest = 0;
        if (!format || *format == "ascii")
        {
          for (const std::string_view word : Words(text))
          {
            largest = std::max(largest, std::strtold(std::string(word).c_str(), nullptr));
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
