#include "MotionTable.h"

#include <algorithm>
#include <cmath>

namespace bender
{

MotionTable::MotionTable(const RibbonWarp& warp)
  : Data(warp.MotionTable())
  , Grid(warp.Grid())
{
}

DualQuaternion MotionTable::At(double s) const
{
  s = std::clamp(s, 0.0, 1.0);
  const Piece& p = this->Grid.PieceOf(s);
  const double u = (s - p.start) * p.scale;
  const int j = std::min(p.offset + static_cast<int>(u), p.last - 1);
  const double a = std::clamp(u - (j - p.offset), 0.0, 1.0);
  const DualQuaternion& m0 = this->Data[j];
  const DualQuaternion& m1 = this->Data[j + 1];
  const double b = 1.0 - a;
  DualQuaternion m;
  m.real = { b * m0.real.w + a * m1.real.w,
    b * m0.real.x + a * m1.real.x,
    b * m0.real.y + a * m1.real.y,
    b * m0.real.z + a * m1.real.z };
  m.dual = { b * m0.dual.w + a * m1.dual.w,
    b * m0.dual.x + a * m1.dual.x,
    b * m0.dual.y + a * m1.dual.y,
    b * m0.dual.z + a * m1.dual.z };
  const double inv = 1.0 / std::sqrt(Dot4(m.real, m.real));
  m.real = { m.real.w * inv, m.real.x * inv, m.real.y * inv, m.real.z * inv };
  m.dual = { m.dual.w * inv, m.dual.x * inv, m.dual.y * inv, m.dual.z * inv };
  // Unit dual quaternions have real . dual = 0.
  const double rd = Dot4(m.real, m.dual);
  m.dual = { m.dual.w - rd * m.real.w,
    m.dual.x - rd * m.real.x,
    m.dual.y - rd * m.real.y,
    m.dual.z - rd * m.real.z };
  return m;
}

} // namespace bender
