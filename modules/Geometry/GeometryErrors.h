#ifndef bender_GeometryErrors_h
#define bender_GeometryErrors_h

#include "BenderErrors.h"

#include <string>
#include <utility>

namespace bender
{

/// Base of the errors thrown by the geometry core for input it cannot use. field() is the
/// part of the warp the problem belongs to, relative to the warp: "initial", "final",
/// "initial.end.tangent", "radius", ... (empty when it concerns the whole input); problem() is
/// the human description without the field; what() is "field: problem". An InputError: the
/// caller's ribbon or warp cannot be used.
class GeometryError : public InputError
{
public:
  GeometryError(std::string field, std::string problem)
    : InputError(field.empty() ? problem : field + ": " + problem)
    , Field(std::move(field))
    , Problem(std::move(problem))
  {
  }
  const std::string& field() const { return this->Field; }
  const std::string& problem() const { return this->Problem; }

private:
  std::string Field;
  std::string Problem;
};

/// A ribbon (its two end frames) that defines no usable wire: non-finite input,
/// coincident ends, a cusp, or the unstable near-parallel case (spec convention 11).
class InvalidRibbonError : public GeometryError
{
public:
  using GeometryError::GeometryError;
};

/// A warp whose ribbons may each be valid but whose whole makes no sense: a turn of more
/// than 340 degrees relative to the grab (spec 4.4), or parameters out of range (radius
/// <= 0, decay plateau outside [0, 0.95]). Not an InvalidRibbonError: catch GeometryError
/// for both.
class InvalidWarpError : public GeometryError
{
public:
  using GeometryError::GeometryError;
};

} // namespace bender

#endif
