#ifndef bender_GeometryErrors_h
#define bender_GeometryErrors_h

#include <stdexcept>
#include <string>

namespace bender
{

/// Base of the errors thrown by the geometry core.
class GeometryError : public std::invalid_argument
{
public:
  using std::invalid_argument::invalid_argument;
};

/// A ribbon (its two end frames) that defines no usable wire: non-finite input,
/// coincident ends, a cusp, or the unstable near-parallel case (spec convention 11).
/// field() is the part of the warp the problem belongs to, relative to the warp:
/// "initial", "final", "initial.end.tangent", ... (empty when it concerns the whole warp);
/// problem() is the human description without the field.
class InvalidRibbonError : public GeometryError
{
public:
  InvalidRibbonError(std::string field, std::string problem)
    : GeometryError(field.empty() ? problem : field + ": " + problem)
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

/// A warp whose two ribbons are each valid but together mean nothing: a turn of more
/// than 340 degrees relative to the grab (spec 4.4), or absurd parameters (R <= 0, ...).
class InvalidWarpError : public InvalidRibbonError
{
public:
  using InvalidRibbonError::InvalidRibbonError;
};

} // namespace bender

#endif
