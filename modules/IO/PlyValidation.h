#ifndef bender_PlyValidation_h
#define bender_PlyValidation_h

// Internal: a structural check of PLY files before vtkPLYReader sees them. VTK 9.1's reader
// frees memory twice on a truncated binary file (abort), so a file is walked element by
// element first and refused unless every announced record is there.

#include <cstdint>
#include <string>

namespace bender
{
namespace io_detail
{

/// True when the file at path is a PLY file (ASCII or binary, either endianness) whose
/// header parses and whose body holds every record the header announces. Otherwise false
/// with problem set ("truncated binary PLY (element \"face\" record 12 of 40 ends past the end
/// of the file)", "unknown property type \"float128\"", ...).
bool CheckPlyStructure(const std::string& path, std::string& problem);

/// The same check on the file's bytes (for the fuzz harness). ASCII bodies must hold one
/// record per line (as vtkPLY reads them), every line shorter than 4000 bytes.
bool CheckPlyBytes(const std::string& data, std::string& problem);

} // namespace io_detail
} // namespace bender

#endif
