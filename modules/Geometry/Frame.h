#ifndef bender_Frame_h
#define bender_Frame_h

#include "Vec3.h"

namespace bender
{

/// A right-handed orthonormal frame C = (O; T, N, B) with B = T x N.
/// As a matrix M = [T N B] (columns).
struct Frame
{
  Vec3 origin;
  Vec3 t{ 1, 0, 0 };
  Vec3 n{ 0, 1, 0 };
  Vec3 b{ 0, 0, 1 };
};

/// The frame with tangent T and normal N at the origin, completed by B = T x N (T and N are
/// taken as given: unit and orthogonal).
inline Frame FrameOfTangentNormal(const Vec3& T, const Vec3& N)
{
  Frame frame;
  frame.t = T;
  frame.n = N;
  frame.b = Cross(T, N);
  return frame;
}

} // namespace bender

#endif
