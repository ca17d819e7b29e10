// FormatReportText, ToJson, FormatReportJson: a MeshCheckReport for people and programs.

#include "BenderMeshCheck.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace bender
{

namespace
{
std::string Number(double v)
{
  if (!std::isfinite(v))
  {
    return "null";
  }
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.9g", v);
  return buffer;
}

} // namespace

std::string FormatReportText(const MeshCheckReport& r, const std::string& name)
{
  std::ostringstream os;
  os << name << ": " << (r.Clean() ? "clean" : "PROBLEMS") << "\n";
  os << "  triangles " << r.triangles << ", points " << r.points;
  if (r.unusedPoints)
  {
    os << " (" << r.unusedPoints << " unused)";
  }
  os << ", components " << r.components << "\n";
  os << "  boundary loops " << r.boundaryLoops.size();
  if (!r.boundaryLoops.empty())
  {
    os << " (edges:";
    for (vtkIdType l : r.boundaryLoops)
    {
      os << " " << l;
    }
    os << ")";
  }
  os << (r.closed ? ", closed" : ", open") << "\n";
  os << "  non-manifold edges " << r.nonManifoldEdges << ", vertices " << r.nonManifoldVertices
     << "; inconsistently oriented edges " << r.inconsistentEdges << "\n";
  os << "  degenerate triangles " << r.degenerateTriangles << "; self-intersections "
     << (r.selfIntersectionsChecked ? std::to_string(r.selfIntersections) : "not checked");
  for (const auto& p : r.intersectingPairs)
  {
    os << " (" << p.first << "," << p.second << ")";
  }
  os << "\n";
  os << "  area " << Number(r.area);
  if (r.closed)
  {
    os << ", volume " << Number(std::abs(r.volume))
       << (r.volume < 0 ? " (triangles face inwards)" : "");
  }
  os << "\n";
  os << "  edge length min " << Number(r.edgeLength.min) << " mean " << Number(r.edgeLength.mean)
     << " max " << Number(r.edgeLength.max) << "\n";
  os << "  minimum angle (deg) min " << Number(r.minimumAngle.min) << " mean "
     << Number(r.minimumAngle.mean) << "\n";
  if (r.flipsChecked)
  {
    os << "  flipped triangles since before the warp " << r.flippedTriangles << "\n";
  }
  else if (!r.flipsNote.empty())
  {
    os << "  " << r.flipsNote << "\n";
  }
  for (const std::string& p : r.problems)
  {
    os << "  problem: " << p << "\n";
  }
  return os.str();
}

nlohmann::ordered_json ToJson(const MeshCheckReport& r, const std::string& name)
{
  using json = nlohmann::ordered_json;
  // Measures that could not be taken (not closed, flips or self-intersections not checked,
  // a non-finite value) are null.
  const auto number = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json out;
  out["mesh"] = name;
  out["clean"] = r.Clean();
  out["triangles"] = r.triangles;
  out["points"] = r.points;
  out["unusedPoints"] = r.unusedPoints;
  out["components"] = r.components;
  out["boundaryEdges"] = r.boundaryEdges;
  out["boundaryLoops"] = r.boundaryLoops;
  out["closed"] = r.closed;
  out["nonManifoldEdges"] = r.nonManifoldEdges;
  out["nonManifoldVertices"] = r.nonManifoldVertices;
  out["inconsistentEdges"] = r.inconsistentEdges;
  out["degenerateTriangles"] = r.degenerateTriangles;
  out["selfIntersections"] = r.selfIntersectionsChecked ? json(r.selfIntersections) : json(nullptr);
  out["intersectingPairs"] = json::array();
  for (const auto& [a, b] : r.intersectingPairs)
  {
    out["intersectingPairs"].push_back({ a, b });
  }
  out["area"] = number(r.area);
  out["volume"] = r.closed ? number(std::abs(r.volume)) : json(nullptr);
  out["facesInward"] = r.closed && r.volume < 0;
  out["edgeLength"] = { { "min", number(r.edgeLength.min) },
    { "mean", number(r.edgeLength.mean) },
    { "max", number(r.edgeLength.max) } };
  out["minimumAngleDegrees"] = { { "min", number(r.minimumAngle.min) },
    { "mean", number(r.minimumAngle.mean) } };
  out["flippedTriangles"] = r.flipsChecked ? json(r.flippedTriangles) : json(nullptr);
  out["nonFinitePoints"] = r.nonFinitePoints;
  out["problems"] = r.problems;
  return out;
}

std::string FormatReportJson(const MeshCheckReport& r, const std::string& name)
{
  // Invalid UTF-8 in a file name is replaced rather than thrown on.
  return ToJson(r, name).dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) +
    "\n";
}

} // namespace bender
