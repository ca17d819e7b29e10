#ifndef bender_OffFormat_h
#define bender_OffFormat_h

// Internal: ASCII OFF (Object File Format) reader and writer; VTK 9.1 has neither.

#include "BenderErrors.h"

#include <vtkSmartPointer.h>

#include <stdexcept>
#include <string>

class vtkPolyData;

namespace bender
{
namespace io_detail
{

/// A malformed OFF file; what() is the problem without the file name ("line 12: ...").
class OffError : public InputError
{
public:
  using InputError::InputError;
};

/// Reads ASCII OFF: an optional "OFF" keyword (also COFF, NOFF, CNOFF, STOFF; vertex columns
/// after x y z are ignored), counts "nv nf [ne]" on the keyword line or the next data line,
/// nv vertex lines, nf face lines "n i1 ... in [colour]". "#" starts a comment anywhere.
/// Coordinates are kept as doubles. Throws OffError for wrong counts, indices out of range,
/// faces with fewer than 3 vertices, malformed or non-finite numbers, binary OFF, or data
/// after the last announced face.
vtkSmartPointer<vtkPolyData> ReadOff(const std::string& path);

/// Writes ASCII OFF with shortest round-trip decimal coordinates (doubles read back
/// bit-identical). Polygons are written as faces, strips as triangles; vertices and lines
/// are not representable and are left out. header becomes a "#" comment line when not empty.
bool WriteOff(vtkPolyData* mesh,
  const std::string& path,
  const std::string& header,
  std::string& problem);

} // namespace io_detail
} // namespace bender

#endif
