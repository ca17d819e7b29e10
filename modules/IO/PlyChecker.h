#ifndef bender_PlyChecker_h
#define bender_PlyChecker_h

// Internal to PlyValidation.cxx and the PLY checks (PlyHeaderCheck.cxx, PlyBodyCheck.cxx): the
// header model and the checker of CheckPlyBytes.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace bender
{
namespace io_detail
{
namespace ply
{

/// vtkPLY reads lines with fgets into a 4096-byte buffer.
constexpr std::size_t MaxPlyLine = 4000;

/// vtkPLYReader keeps a face's vertex count in one byte and copies it into 256 ids.
constexpr std::int64_t MaxFaceVertices = 255;

struct ScalarType
{
  int size = 0;
  bool isSigned = false;
  bool isInteger = true;
};

struct Property
{
  std::string name;
  bool isList = false;
  ScalarType count; // lists only
  ScalarType item;  // the scalar, or each list item
  bool isFaceIndices = false;
};

struct Element
{
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

/// vtkPLY 9.1's type names; false for another name.
bool ParseType(std::string_view name, ScalarType& type);

/// The range of an integer type.
std::int64_t MinValue(const ScalarType& type);
std::int64_t MaxValue(const ScalarType& type);

/// Words as vtkPLY splits a line: at spaces and tabs.
std::vector<std::string_view> SplitWords(std::string_view line);

/// One little- or big-endian integer of 1, 2 or 4 bytes.
std::int64_t DecodeInteger(const unsigned char* p, const ScalarType& type, bool bigEndian);

/// "element "face" record 3 of 12".
std::string Where(const Element& element, std::uint64_t record);

/// An integer, a leading '+' allowed.
bool ParseInteger(std::string_view token, std::int64_t& value);

/// A real number as atof reads it (overflow reads as inf), a leading '+' allowed.
bool ParseReal(std::string_view token);

// What vtkPLYReader (VTK 9.1) and the vtkPLY library under it read safely, accepted as a
// whitelist; anything else is refused before the reader runs (docs/input-validation.md):
// - the header: "ply", "format ascii|binary_little_endian|binary_big_endian 1.0", "comment"
//   and "obj_info" lines, "element NAME COUNT", "property TYPE NAME" and "property list
//   COUNT_TYPE ITEM_TYPE NAME" with vtkPLY's type names, "end_header"; each line exactly its
//   words (vtkPLY reads missing words from an uninitialised array), at most 4000 bytes
//   (vtkPLY's line buffer is 4096 bytes), printable ASCII and tabs only (vtkPLY splits words
//   at spaces and tabs alone), no element or property named twice, and "vertex_index" only as
//   a property name (vtkPLY rewrites that word in place as "vertex_indices" on every line);
// - the elements: "vertex" with scalar x, y and z and no lists; "face", after "vertex", with
//   exactly one "vertex_indices" or "vertex_index" list of integers and no other list (the
//   reader reads scalars into a fixed record); any other element after both (the reader never
//   reads it, so one before them would shift what it reads);
// - the records, against the declared types: ASCII one record per line with exactly its
//   values, integers where the type is an integer, faces of 3 to 255 vertices (the reader
//   keeps a byte of the count) with indices below the vertex count; binary exactly as long as
//   the records, with the same bounds on lists and indices.
class PlyChecker
{
public:
  explicit PlyChecker(const std::string& data)
    : Data(data)
  {
  }

  bool Check(std::string& problem)
  {
    return this->ReadHeader(problem) && this->CheckElements(problem) &&
      (this->Ascii ? this->CheckAsciiBody(problem) : this->CheckBinaryBody(problem));
  }

private:
  const std::string& Data;
  std::size_t Position = 0; // first byte after the header
  std::size_t LineNumber = 0;
  bool Ascii = false;
  bool BigEndian = false;
  std::vector<Element> Elements;
  std::int64_t VertexCount = 0;
  bool ReadHeader(std::string& problem);
  bool CheckElements(std::string& problem);
  bool BadIndex(const Element& element, std::uint64_t r, std::int64_t index, std::string& problem);
  bool CheckAsciiBody(std::string& problem);
  bool CheckBinaryBody(std::string& problem);
};

} // namespace ply
} // namespace io_detail
} // namespace bender

#endif
