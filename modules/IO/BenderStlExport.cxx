#include "BenderStlExport.h"

#include "AtomicFile.h"
#include "BenderErrors.h"
#include "CoordinateRange.h"
#include "FileUtilities.h"
#include "StringUtil.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <memory>

namespace bender
{
namespace
{

struct Facet
{
  std::array<float, 3> n;
  std::array<std::array<float, 3>, 3> v;
};

// Triangles of the polygons (fanned) and strips of mesh, each with the id of its cell.
void Triangulate(vtkPolyData* mesh,
  std::vector<std::array<vtkIdType, 3>>& tris,
  std::vector<vtkIdType>& cells)
{
  vtkIdType cell = mesh->GetNumberOfVerts() + mesh->GetNumberOfLines();
  if (vtkCellArray* polys = mesh->GetPolys())
  {
    auto it = vtk::TakeSmartPointer(polys->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cell)
    {
      vtkIdType npts;
      const vtkIdType* pts;
      it->GetCurrentCell(npts, pts);
      for (vtkIdType k = 1; k + 1 < npts; ++k)
      {
        tris.push_back({ pts[0], pts[k], pts[k + 1] });
        cells.push_back(cell);
      }
    }
  }
  if (vtkCellArray* strips = mesh->GetStrips())
  {
    auto it = vtk::TakeSmartPointer(strips->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cell)
    {
      vtkIdType npts;
      const vtkIdType* pts;
      it->GetCurrentCell(npts, pts);
      for (vtkIdType k = 0; k + 2 < npts; ++k)
      {
        if (k % 2 == 0)
        {
          tris.push_back({ pts[k], pts[k + 1], pts[k + 2] });
        }
        else
        {
          tris.push_back({ pts[k + 1], pts[k], pts[k + 2] });
        }
        cells.push_back(cell);
      }
    }
  }
}

// Throws for a corner of a triangle outside the coordinate range (CoordinateRange.h).
void CheckFinite(vtkPolyData* mesh, const std::vector<std::array<vtkIdType, 3>>& tris)
{
  for (const auto& tri : tris)
  {
    for (vtkIdType id : tri)
    {
      double p[3];
      mesh->GetPoint(id, p);
      if (!InMeshCoordinateRange(p))
      {
        throw StlExportError("point " + std::to_string(id) + ": " + CoordinateRangeProblem(p));
      }
    }
  }
}

// The facets of every patch (index as in labels.patches), in the written coordinates.
std::vector<std::vector<Facet>> Facets(vtkPolyData* mesh,
  const LabelledTriangles& labels,
  const ExportTransform& transform,
  bool perPatch)
{
  std::vector<std::vector<Facet>> out(perPatch ? labels.patches.size() : 1);
  for (std::size_t t = 0; t < labels.triangles.size(); ++t)
  {
    std::array<std::array<double, 3>, 3> p;
    for (int k = 0; k < 3; ++k)
    {
      double in[3];
      mesh->GetPoint(labels.triangles[t][k], in);
      transform.Apply(in, p[k].data());
      if (!InMeshCoordinateRange(p[k].data()))
      {
        throw StlExportError("point " + std::to_string(labels.triangles[t][k]) + " in " +
          StlFrameName(transform.Frame()) + " " + transform.Unit() + ": " +
          CoordinateRangeProblem(p[k].data()));
      }
    }
    const double u[3] = { p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2] };
    const double w[3] = { p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2] };
    const double n[3] = {
      u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]
    };
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    Facet f;
    for (int a = 0; a < 3; ++a)
    {
      f.n[a] = static_cast<float>(len > 0 ? n[a] / len : 0.0);
      for (int k = 0; k < 3; ++k)
      {
        f.v[k][a] = static_cast<float>(p[k][a]);
      }
    }
    out[perPatch ? labels.patch[t] : 0].push_back(f);
  }
  return out;
}

// A producer for the atomic write: opens the temporary file and runs write on it.
FileProducer Producer(std::function<bool(std::FILE*)> write)
{
  return [write = std::move(write)](const std::string& temp, std::string& problem)
  {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(temp.c_str(), "wb"), &std::fclose);
    if (!f)
    {
      problem = std::string("cannot create a file there (") + std::strerror(errno) + ")";
      return false;
    }
    if (!write(f.get()) || std::fflush(f.get()) != 0 || std::fclose(f.release()) != 0)
    {
      problem = std::string("write failed (") + std::strerror(errno) + ")";
      return false;
    }
    return true;
  };
}

std::string Header(const StlExportOptions& options)
{
  return std::string("bender export: frame ") + StlFrameName(options.frame) + ", unit " +
    options.unit;
}

bool WriteBinary(std::FILE* f, const std::string& header, const std::vector<Facet>& facets)
{
  char head[80];
  std::memset(head, ' ', sizeof(head));
  std::memcpy(head, header.data(), std::min<std::size_t>(header.size(), sizeof(head)));
  const auto count = static_cast<std::uint32_t>(facets.size());
  bool ok = std::fwrite(head, 1, 80, f) == 80 && std::fwrite(&count, 4, 1, f) == 1;
  const std::uint16_t attribute = 0;
  for (const Facet& facet : facets)
  {
    ok = ok && std::fwrite(facet.n.data(), 4, 3, f) == 3;
    for (const auto& v : facet.v)
    {
      ok = ok && std::fwrite(v.data(), 4, 3, f) == 3;
    }
    ok = ok && std::fwrite(&attribute, 2, 1, f) == 1;
  }
  return ok;
}

bool WriteSolid(std::FILE* f,
  const std::string& name,
  const std::string& endNote,
  const std::vector<Facet>& facets)
{
  bool ok = std::fprintf(f, "solid %s\n", name.c_str()) > 0;
  for (const Facet& facet : facets)
  {
    ok = ok &&
      std::fprintf(
        f, "  facet normal %.9g %.9g %.9g\n    outer loop\n", facet.n[0], facet.n[1], facet.n[2]) >
        0;
    for (const auto& v : facet.v)
    {
      ok = ok && std::fprintf(f, "      vertex %.9g %.9g %.9g\n", v[0], v[1], v[2]) > 0;
    }
    ok = ok && std::fprintf(f, "    endloop\n  endfacet\n") > 0;
  }
  return ok && std::fprintf(f, "endsolid %s%s\n", name.c_str(), endNote.c_str()) > 0;
}

std::string StlStem(const std::string& path)
{
  std::string stem = path;
  if (stem.size() > 4 &&
    (stem.compare(stem.size() - 4, 4, ".stl") == 0 ||
      stem.compare(stem.size() - 4, 4, ".STL") == 0))
  {
    stem.resize(stem.size() - 4);
  }
  return stem;
}
} // namespace

const char* StlFrameName(StlFrame frame)
{
  return frame == StlFrame::RAS ? "RAS" : "LPS";
}

bool IsExportUnit(const std::string& unit)
{
  return unit == "mm" || unit == "m";
}

ExportTransform::ExportTransform(StlFrame frame, const std::string& unit)
  : FrameValue(frame)
  , UnitValue(unit)
  , Metres(unit == "m")
{
  if (!IsExportUnit(unit))
  {
    throw StlExportError("unknown unit '" + unit + "' (expected mm or m)");
  }
}

void ExportTransform::Apply(const double in[3], double out[3]) const
{
  const double sign = this->FrameValue == StlFrame::RAS ? -1.0 : 1.0;
  out[0] = sign * in[0];
  out[1] = sign * in[1];
  out[2] = in[2];
  if (this->Metres)
  {
    for (int a = 0; a < 3; ++a)
    {
      out[a] /= 1000.0;
    }
  }
}

std::vector<std::size_t> LabelledTriangles::CountPerPatch() const
{
  std::vector<std::size_t> counts(this->patches.size(), 0);
  for (std::size_t p : this->patch)
  {
    ++counts[p];
  }
  return counts;
}

LabelledTriangles CollectLabelledTriangles(const LabelledSurface& mesh)
{
  if (!mesh.surface)
  {
    throw StlExportError("no mesh to export");
  }
  LabelledTriangles out;
  std::vector<vtkIdType> cells;
  Triangulate(mesh.surface, out.triangles, cells);
  if (out.triangles.empty())
  {
    throw StlExportError("the mesh has no triangles");
  }
  CheckFinite(mesh.surface, out.triangles);
  std::vector<int> ids;
  try
  {
    ids = CellPatchIds(mesh.surface);
  }
  catch (const InputError& e)
  {
    throw StlExportError(e.what());
  }
  out.patches = mesh.patches;
  std::map<int, std::size_t> index;
  for (std::size_t k = 0; k < out.patches.size(); ++k)
  {
    index[out.patches[k].id] = k;
  }
  out.patch.reserve(cells.size());
  for (vtkIdType cell : cells)
  {
    const int id = ids[static_cast<std::size_t>(cell)];
    const auto found = index.find(id);
    if (found == index.end())
    {
      // A table taken from another surface: say so rather than write a patch without a name.
      throw StlExportError("patch id " + std::to_string(id) + " of cell " + std::to_string(cell) +
        " is not in the surface's patch table");
    }
    out.patch.push_back(found->second);
  }
  return out;
}

LabelledSurface ReadExportLabels(vtkPolyData* mesh, const std::string& path)
{
  try
  {
    return ReadLabelledSurface(mesh);
  }
  catch (const InputError& e)
  {
    throw StlExportError(DisplayName(path) + ": " + e.what());
  }
}

std::vector<std::string> PatchNames(const LabelledSurface& mesh)
{
  std::vector<std::string> names;
  for (const PatchLabel& label : mesh.patches)
  {
    names.push_back(label.name);
  }
  if (names.empty())
  {
    names.push_back("wall");
  }
  return names;
}

std::vector<std::string> PlannedStlPaths(const LabelledSurface& mesh,
  const std::string& path,
  const StlExportOptions& options)
{
  if (options.patches != StlPatchMode::Files)
  {
    return { path };
  }
  LabelledTriangles labels;
  try
  {
    labels = CollectLabelledTriangles(mesh);
  }
  catch (const StlExportError& e)
  {
    throw StlExportError(DisplayName(path) + ": " + e.what());
  }
  const std::vector<std::size_t> counts = labels.CountPerPatch();
  std::vector<std::string> paths;
  for (std::size_t k = 0; k < labels.patches.size(); ++k)
  {
    if (counts[k] > 0)
    {
      paths.push_back(StlStem(path) + "_" + labels.patches[k].name + ".stl");
    }
  }
  return paths;
}

std::vector<AtomicFile> StlFiles(const LabelledSurface& mesh,
  const std::string& path,
  const StlExportOptions& options)
{
  LabelledTriangles labels;
  std::vector<std::vector<Facet>> facets;
  try
  {
    const ExportTransform transform(options.frame, options.unit);
    labels = CollectLabelledTriangles(mesh);
    facets = Facets(mesh.surface, labels, transform, options.patches != StlPatchMode::Single);
  }
  catch (const StlExportError& e)
  {
    throw StlExportError(DisplayName(path) + ": " + e.what());
  }
  // The facets are shared by the producers, which may run after this function returned.
  auto shared = std::make_shared<std::vector<std::vector<Facet>>>(std::move(facets));
  const std::string header = Header(options);
  std::vector<AtomicFile> files;
  switch (options.patches)
  {
    case StlPatchMode::Single:
      files.push_back({ path,
        Producer(
          [shared, header](std::FILE* f) { return WriteBinary(f, header, (*shared)[0]); }) });
      break;
    case StlPatchMode::Solids:
    {
      std::vector<std::string> names;
      for (const PatchLabel& label : labels.patches)
      {
        names.push_back(label.name);
      }
      files.push_back({ path,
        Producer(
          [shared, names, header](std::FILE* f)
          {
            // ASCII STL has no comment: the header follows the first solid's name on its
            // endsolid line, which readers ignore (OpenFOAM would fold it into the patch name
            // on the solid line).
            bool ok = true;
            bool first = true;
            for (std::size_t k = 0; k < names.size(); ++k)
            {
              if ((*shared)[k].empty())
              {
                continue;
              }
              ok =
                ok && WriteSolid(f, names[k], first ? "  " + header : std::string(), (*shared)[k]);
              first = false;
            }
            return ok;
          }) });
      break;
    }
    case StlPatchMode::Files:
    {
      // All patches or none: a case with the wall but without its inlets is worse than none.
      const std::string stem = StlStem(path);
      for (std::size_t k = 0; k < labels.patches.size(); ++k)
      {
        if ((*shared)[k].empty())
        {
          continue;
        }
        const std::string fileHeader = header + ", patch " + labels.patches[k].name;
        files.push_back({ stem + "_" + labels.patches[k].name + ".stl",
          Producer([fileHeader, shared, k](std::FILE* f)
            { return WriteBinary(f, fileHeader, (*shared)[k]); }) });
      }
      break;
    }
  }
  return files;
}

std::vector<std::string> ExportStl(vtkPolyData* mesh,
  const std::string& path,
  const StlExportOptions& options)
{
  if (!mesh)
  {
    throw StlExportError(DisplayName(path) + ": no mesh to export");
  }
  const std::vector<AtomicFile> files = StlFiles(ReadExportLabels(mesh, path), path, options);
  std::string problem;
  if (!AtomicWriteAll(files, problem))
  {
    throw StlExportError(problem);
  }
  std::vector<std::string> written;
  for (const AtomicFile& file : files)
  {
    written.push_back(file.path);
  }
  return written;
}

bool WriteStlFile(vtkPolyData* mesh,
  const std::string& path,
  bool binary,
  const std::string& header,
  std::string& problem)
{
  if (!mesh)
  {
    problem = "no mesh to write";
    return false;
  }
  // Labels play no part here: the whole surface, as it is.
  LabelledTriangles whole;
  std::vector<vtkIdType> cells;
  Triangulate(mesh, whole.triangles, cells);
  if (whole.triangles.empty())
  {
    problem = "the mesh has no triangles";
    return false;
  }
  whole.patch.assign(whole.triangles.size(), 0);
  std::vector<std::vector<Facet>> facets;
  try
  {
    CheckFinite(mesh, whole.triangles);
    facets = Facets(mesh, whole, ExportTransform(StlFrame::LPS, "mm"), false);
  }
  catch (const StlExportError& e)
  {
    problem = e.what();
    return false;
  }
  // One line; a binary header starting with "solid" would make readers take it for ASCII.
  std::string line = header.substr(0, header.find_first_of("\r\n"));
  if (binary && line.compare(0, 5, "solid") == 0)
  {
    line = "# " + line;
  }
  return Producer(
    [&](std::FILE* f)
    {
      return binary ? WriteBinary(f, line, facets[0])
                    : WriteSolid(f, line.empty() ? "mesh" : line, std::string(), facets[0]);
    })(path, problem);
}

} // namespace bender
