#include "MotionTable.h"

#include <algorithm>
#include <cmath>

namespace bender
{

MotionTable::MotionTable(const RibbonWarp& warp, int samples)
{
  std::vector<double> knots = { 0.0, warp.Initial().Wire().JunctionParameter(),
    warp.Final().Wire().JunctionParameter(), 1.0 };
  std::sort(knots.begin(), knots.end());
  // Drop knots closer than one sample spacing to the previous one: such a piece would be too
  // short to matter and would cost a sample budget of its own.
  const double minPiece = 1.0 / std::max(samples, 2);
  std::vector<double> kept = { 0.0 };
  for (std::size_t i = 1; i + 1 < knots.size(); ++i)
  {
    if (knots[i] - kept.back() >= minPiece && 1.0 - knots[i] >= minPiece)
    {
      kept.push_back(knots[i]);
    }
  }
  kept.push_back(1.0);
  int offset = 0;
  for (std::size_t k = 0; k + 1 < kept.size(); ++k)
  {
    Piece p;
    p.start = kept[k];
    p.end = kept[k + 1];
    const double length = p.end - p.start;
    const int n = std::max(2, static_cast<int>(std::ceil(length * (samples - 1))) + 1);
    p.scale = (n - 1) / length;
    p.offset = offset;
    p.last = offset + n - 1;
    for (int j = 0; j < n; ++j)
    {
      const double s = j + 1 == n ? p.end : p.start + j / p.scale;
      this->Data.push_back(warp.MotionAt(s));
    }
    offset += n;
    this->Parts.push_back(p);
  }
}

DualQuaternion MotionTable::At(double s) const
{
  s = std::clamp(s, 0.0, 1.0);
  std::size_t k = 0;
  while (k + 1 < this->Parts.size() && s >= this->Parts[k].end)
  {
    ++k;
  }
  const Piece& p = this->Parts[k];
  const double u = (s - p.start) * p.scale;
  const int j = std::min(p.offset + static_cast<int>(u), p.last - 1);
  const double a = std::clamp(u - (j - p.offset), 0.0, 1.0);
  const DualQuaternion& m0 = this->Data[j];
  const DualQuaternion& m1 = this->Data[j + 1];
  const double b = 1.0 - a;
  DualQuaternion m;
  m.real = { b * m0.real.w + a * m1.real.w, b * m0.real.x + a * m1.real.x,
    b * m0.real.y + a * m1.real.y, b * m0.real.z + a * m1.real.z };
  m.dual = { b * m0.dual.w + a * m1.dual.w, b * m0.dual.x + a * m1.dual.x,
    b * m0.dual.y + a * m1.dual.y, b * m0.dual.z + a * m1.dual.z };
  const double inv = 1.0 / std::sqrt(Dot4(m.real, m.real));
  m.real = { m.real.w * inv, m.real.x * inv, m.real.y * inv, m.real.z * inv };
  m.dual = { m.dual.w * inv, m.dual.x * inv, m.dual.y * inv, m.dual.z * inv };
  // Unit dual quaternions have real . dual = 0.
  const double rd = Dot4(m.real, m.dual);
  m.dual = { m.dual.w - rd * m.real.w, m.dual.x - rd * m.real.x, m.dual.y - rd * m.real.y,
    m.dual.z - rd * m.real.z };
  return m;
}

} // namespace bender
