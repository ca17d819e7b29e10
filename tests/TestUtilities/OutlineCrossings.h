#ifndef bender_OutlineCrossings_h
#define bender_OutlineCrossings_h

// Whether drawn lines are simple closed curves on the screen: the loops of a polydata's lines in
// a renderer's display coordinates, and the crossings of their segments (the region outline of
// the ribbon widget, issue 22).

#include <vtkCellArray.h>
#include <vtkInteractorObserver.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>

#include <array>
#include <utility>
#include <vector>

namespace bendertest
{

using ScreenPoint = std::array<double, 2>;
using ScreenLoop = std::vector<ScreenPoint>;

/// Every polyline of `lines` as its points in display coordinates of `renderer`.
inline std::vector<ScreenLoop> DisplayLoops(vtkPolyData* lines, vtkRenderer* renderer)
{
  std::vector<ScreenLoop> loops;
  vtkCellArray* cells = lines->GetLines();
  vtkIdType count = 0;
  const vtkIdType* ids = nullptr;
  for (cells->InitTraversal(); cells->GetNextCell(count, ids);)
  {
    ScreenLoop loop;
    for (vtkIdType i = 0; i < count; ++i)
    {
      double p[3], d[3];
      lines->GetPoint(ids[i], p);
      vtkInteractorObserver::ComputeWorldToDisplay(renderer, p[0], p[1], p[2], d);
      loop.push_back({ d[0], d[1] });
    }
    loops.push_back(loop);
  }
  return loops;
}

/// Twice the signed area of the triangle abc (> 0 counter-clockwise).
inline double Orientation(const ScreenPoint& a, const ScreenPoint& b, const ScreenPoint& c)
{
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/// Whether the segments ab and cd cross at a point inside both (touching does not count).
inline bool SegmentsCross(const ScreenPoint& a,
  const ScreenPoint& b,
  const ScreenPoint& c,
  const ScreenPoint& d)
{
  const double d1 = Orientation(c, d, a), d2 = Orientation(c, d, b);
  const double d3 = Orientation(a, b, c), d4 = Orientation(a, b, d);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

/// The crossings of the loops' segments, with themselves and with each other.
inline int Crossings(const std::vector<ScreenLoop>& loops)
{
  std::vector<std::pair<ScreenPoint, ScreenPoint>> segments;
  for (const ScreenLoop& loop : loops)
  {
    for (std::size_t i = 0; i + 1 < loop.size(); ++i)
    {
      segments.push_back({ loop[i], loop[i + 1] });
    }
  }
  int crossings = 0;
  for (std::size_t i = 0; i < segments.size(); ++i)
  {
    for (std::size_t j = i + 1; j < segments.size(); ++j)
    {
      crossings +=
        SegmentsCross(segments[i].first, segments[i].second, segments[j].first, segments[j].second)
        ? 1
        : 0;
    }
  }
  return crossings;
}

/// True when `loops` is one closed curve of at least `points` points that never crosses itself.
inline bool IsSimpleClosedCurve(const std::vector<ScreenLoop>& loops, std::size_t points = 8)
{
  return loops.size() == 1 && loops.front().size() >= points &&
    loops.front().front() == loops.front().back() && Crossings(loops) == 0;
}

} // namespace bendertest

#endif
