#ifndef bender_InputValidation_h
#define bender_InputValidation_h

// Internal: pre-validators that model what the VTK readers assume, run on the whole file
// before the reader sees it, and the cleaner that turns library messages into one safe line.
// Every function takes the file's bytes (so that the libFuzzer harnesses in fuzz/ can call it
// directly), never throws for any input, and answers false with a one-line problem.
// See docs/input-validation.md.

#include <cstdint>
#include <string>
#include <string_view>

namespace bender
{
namespace io_detail
{

/// Memory budget for mesh files: larger files are refused before any reader allocates.
constexpr std::uint64_t MaxMeshFileBytes = std::uint64_t(1) << 30; // 1 GiB

/// One line fit for an error message, from text produced by VTK, ITK, teem (NRRD) or a file:
/// drops the "ERROR: In file.cxx, line N", "vtkClass (0x...): ", "itk::ERROR: Class(0x...): ",
/// "ITK ERROR: ..." and "[nrrd] func:" prefixes, ANSI escape sequences, joins lines with "; ",
/// escapes every other non-printable byte as \xNN, collapses runs of blanks and cuts the
/// result to maxLength bytes ("..." at the end). Never empty: "unknown error" when nothing
/// is left.
std::string CleanMessage(std::string_view raw, std::size_t maxLength = 200);

/// A short quote of file bytes for a message: non-printables escaped as \xNN, at most
/// maxLength bytes of output.
std::string QuoteBytes(std::string_view bytes, std::size_t maxLength = 40);

/// Legacy VTK polydata ("# vtk DataFile Version x.y", ASCII or BINARY, versions 1.0 to 5.1):
/// every section is walked with the counts it announces: lines of at most 255 bytes, numeric
/// ASCII values, binary blocks present, cell sizes that add up, 5.1 offsets that start at 0,
/// never decrease and end at the connectivity size, point ids in range, attribute arrays of
/// the announced length, only keywords vtkPolyDataReader knows; string arrays (FIELD arrays of
/// type "string", as Bender's patch names are written) with every value bounded and, in ASCII,
/// well-formed "%XX" escapes.
bool CheckLegacyVtk(std::string_view data, std::string& problem);

/// ASCII STL as vtkSTLReader reads it: one or more "solid ... endsolid" blocks of
/// "facet normal x y z / outer loop / vertex x y z (3 times) / endloop / endfacet", numbers
/// that parse, lines of at most 4000 bytes (VTK 9.1's ASCII parser allocates wildly or
/// misreads anything else).
bool CheckAsciiStl(std::string_view data, std::string& problem);

/// OBJ as vtkOBJReader reads it: lines of at most 8000 bytes, "v" lines with 3 finite numbers,
/// and every vertex, texture-coordinate and normal index of "f", "l" and "p" lines between 1
/// and the number of "v", "vt" and "vn" lines (vtkOBJReader reads normals and texture
/// coordinates by index without checking; relative negative indices are not supported).
bool CheckObj(std::string_view data, std::string& problem);

/// VTK XML files (.vtp, .vti): the root element is <VTKFile type="expectedType"> with a known
/// byte_order, header_type (UInt32/UInt64) and compressor; every DataArray has a known type,
/// 1 to 64 components and a size (NumberOfPoints, NumberOfCells, extent) whose data fits the
/// memory budget; appended data is present (the file ends with </VTKFile>), and the appended
/// blocks' headers lie inside the file; compressed block headers (raw or base64 appended,
/// inline binary) announce blocks within the file and the budget.
bool CheckVtkXml(std::string_view data,
  std::string_view expectedType,
  std::uint64_t budgetBytes,
  std::string& problem);

} // namespace io_detail
} // namespace bender

#endif
