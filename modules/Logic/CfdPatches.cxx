#include "CfdPatches.h"

#include "BenderErrors.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>

namespace bender
{

namespace
{
constexpr double kPi = 3.14159265358979323846;

/// outlet_N, the name an outlet gets from the clip.
bool IsOutletName(const std::string& name)
{
  const std::string prefix = "outlet_";
  return name.size() > prefix.size() && name.compare(0, prefix.size(), prefix) == 0 &&
    name.find_first_not_of("0123456789", prefix.size()) == std::string::npos;
}

/// Applies `rename` to every name of both tables.
template<typename F>
void Rename(std::vector<CfdPatch>& patches, std::vector<PatchLabel>& labels, const F& rename)
{
  for (CfdPatch& p : patches)
  {
    p.name = rename(p.name);
  }
  for (PatchLabel& l : labels)
  {
    l.name = rename(l.name);
  }
}
} // namespace

bool IsEndPatch(PatchType type)
{
  return type != PatchType::Wall;
}

std::vector<std::size_t> EndPatches(const std::vector<CfdPatch>& patches)
{
  std::vector<std::size_t> ends;
  for (std::size_t i = 0; i < patches.size(); ++i)
  {
    if (IsEndPatch(patches[i].type))
    {
      ends.push_back(i);
    }
  }
  return ends;
}

std::vector<CfdPatch> CfdPatchesOf(const PatchSidecar& measured, const std::string& name)
{
  if (!(measured.volume > 0.0) || !std::isfinite(measured.volume))
  {
    throw InputError(name + ": the surface encloses no volume");
  }
  std::vector<CfdPatch> patches;
  for (const PatchGeometry& g : measured.patches)
  {
    CfdPatch p;
    p.name = g.label.name;
    p.type = g.label.type;
    p.triangles = static_cast<long long>(g.triangles);
    p.area = g.area * 1e-6;
    if (g.area > 0.0)
    {
      for (std::size_t k = 0; k < 3; ++k)
      {
        p.centre[k] = 1e-3 * g.areaMoment[k] / g.area;
      }
    }
    // Every patch's own direction, the wall's too (its area vectors nearly cancel).
    const double norm = std::sqrt(g.vectorArea[0] * g.vectorArea[0] +
      g.vectorArea[1] * g.vectorArea[1] + g.vectorArea[2] * g.vectorArea[2]);
    if (norm > 0.0)
    {
      for (std::size_t k = 0; k < 3; ++k)
      {
        p.normal[k] = g.vectorArea[k] / norm;
      }
    }
    p.diameter = 2.0 * std::sqrt(p.area / kPi);
    patches.push_back(p);
  }
  return patches;
}

std::size_t ChooseInlet(std::vector<CfdPatch>& patches,
  LabelledSurface& labelled,
  const std::string& inlet,
  const std::string& name)
{
  const std::vector<std::size_t> ends = EndPatches(patches);
  std::string names;
  for (const std::size_t i : ends)
  {
    names += (names.empty() ? "" : ", ") + patches[i].name;
  }
  std::size_t chosen = patches.size();
  if (!inlet.empty())
  {
    for (std::size_t i = 0; i < patches.size(); ++i)
    {
      if (patches[i].name == inlet)
      {
        chosen = i;
      }
    }
    if (chosen == patches.size())
    {
      throw InputError("--inlet " + inlet + ": " + name + " has no such end (ends: " + names + ")");
    }
    if (!IsEndPatch(patches[chosen].type))
    {
      throw InputError("--inlet " + inlet + ": is the wall, not an end (ends: " + names + ")");
    }
  }
  else
  {
    std::string inlets;
    for (const std::size_t i : ends)
    {
      if (patches[i].type == PatchType::Inlet)
      {
        inlets += (inlets.empty() ? "" : ", ") + patches[i].name;
        if (chosen != patches.size())
        {
          throw InputError(name + ": several inlets (" + inlets + "...): choose one with --inlet");
        }
        chosen = i;
      }
    }
    if (chosen == patches.size())
    {
      throw InputError(
        name + ": no end is labelled inlet: name it with --inlet (ends: " + names + ")");
    }
  }
  for (const std::size_t i : ends)
  {
    patches[i].type = i == chosen ? PatchType::Inlet : PatchType::Outlet;
  }
  std::vector<PatchLabel> labels = labelled.patches;
  for (PatchLabel& l : labels)
  {
    if (IsEndPatch(l.type))
    {
      l.type = l.name == patches[chosen].name ? PatchType::Inlet : PatchType::Outlet;
    }
  }
  // Names that say the roles: "inlet" goes to the chosen end, its outlet_N to the old inlet.
  const std::string old = patches[chosen].name;
  if (old != "inlet")
  {
    const bool outlet = IsOutletName(old);
    std::string free = old;
    for (int k = 1; !outlet; ++k)
    {
      free = "outlet_" + std::to_string(k);
      if (std::none_of(
            patches.begin(), patches.end(), [&free](const CfdPatch& p) { return p.name == free; }))
      {
        break;
      }
    }
    Rename(patches,
      labels,
      [&](const std::string& n)
      { return n == "inlet" ? free : (outlet && n == old ? "inlet" : n); });
  }
  if (std::equal(labels.begin(),
        labels.end(),
        labelled.patches.begin(),
        labelled.patches.end(),
        [](const PatchLabel& a, const PatchLabel& b)
        { return a.id == b.id && a.name == b.name && a.type == b.type; }))
  {
    return chosen;
  }
  // A deep copy: a shallow one shares the field data (PatchNames), and the caller's surface
  // must keep its names.
  vtkNew<vtkPolyData> renamed;
  renamed->DeepCopy(labelled.surface);
  WritePatchLabels(renamed, CellPatchIds(labelled.surface), labels);
  labelled.surface = renamed;
  labelled.patches = labels;
  return chosen;
}

std::array<double, 3> InsidePoint(const PatchSidecar& measured,
  double cellSize,
  const std::string& name)
{
  if (!measured.hasInsidePoint)
  {
    throw InputError(name +
      ": no point inside the lumen was found behind its ends (is the "
      "surface oriented consistently and closed?)");
  }
  // Metres, nudged off the background grid's planes (a fraction of a cell: far less than the
  // point's distance to the wall).
  std::array<double, 3> x{};
  for (std::size_t k = 0; k < 3; ++k)
  {
    x[k] = 1e-3 * measured.insidePoint[k] + (0.0173 + 0.0119 * static_cast<double>(k)) * cellSize;
  }
  return x;
}

} // namespace bender
