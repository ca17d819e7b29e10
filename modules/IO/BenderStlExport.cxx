#include "BenderStlExport.h"

#include "AtomicFile.h"
#include "FileUtilities.h"
#include "MeshTopology.h"
#include "vtkBenderCapFilter.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>

namespace bender
{
namespace
{
using io_detail::DisplayName;

struct Facet
{
  std::array<float, 3> n;
  std::array<std::array<float, 3>, 3> v;
};

std::vector<std::vector<Facet>> Facets(vtkPolyData* mesh, StlFrame frame, std::size_t patches)
{
  const std::vector<std::int64_t> tris = CollectTriangles(mesh);
  if (tris.empty())
  {
    throw StlExportError("the mesh has no triangles");
  }
  vtkDataArray* ids = mesh->GetCellData()->GetArray(vtkBenderCapFilter::PatchIdArrayName());
  // Triangles come from polygons then strips; PatchId is per cell, one triangle per cell for
  // the triangle meshes the cap filter writes.
  const bool perTriangle =
    ids && ids->GetNumberOfTuples() == static_cast<vtkIdType>(tris.size() / 3);
  if (ids && !perTriangle && patches > 1)
  {
    // Labels of polygons or strips cannot be split per patch here: say so rather than put
    // every facet in the wall (the inlets and outlets would vanish from the CFD case).
    throw StlExportError("the PatchId labels are not one per triangle (the surface has polygons, "
                         "strips, lines or vertices): triangulate it before exporting patches");
  }
  std::vector<std::vector<Facet>> out(patches);
  const double sign = frame == StlFrame::RAS ? -1.0 : 1.0;
  for (std::size_t t = 0; t < tris.size(); t += 3)
  {
    std::array<std::array<double, 3>, 3> p;
    for (int k = 0; k < 3; ++k)
    {
      mesh->GetPoint(tris[t + k], p[k].data());
      p[k][0] *= sign;
      p[k][1] *= sign;
      for (double c : p[k])
      {
        if (!std::isfinite(c))
        {
          throw StlExportError("the mesh has non-finite (NaN or infinite) coordinates");
        }
      }
    }
    const double u[3] = { p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2] };
    const double w[3] = { p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2] };
    double n[3] = {
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
    std::size_t patch = 0;
    if (perTriangle && patches > 1)
    {
      const double id = ids->GetTuple1(static_cast<vtkIdType>(t / 3));
      patch = id >= 0 && id < static_cast<double>(patches) ? static_cast<std::size_t>(id) : 0;
    }
    out[patch].push_back(f);
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

// Writes every file of the export or none (the patches of one case belong together).
void WriteAll(const std::vector<AtomicFile>& files)
{
  std::string problem;
  if (!AtomicWriteAll(files, problem))
  {
    throw StlExportError(problem);
  }
}

std::string Header(const StlExportOptions& options)
{
  return std::string("bender export: frame ") + (options.frame == StlFrame::LPS ? "LPS" : "RAS") +
    ", unit " + options.unit;
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
} // namespace

std::vector<std::string> PatchNames(vtkPolyData* mesh)
{
  std::vector<std::string> names{ "wall" };
  vtkDataArray* ids =
    mesh ? mesh->GetCellData()->GetArray(vtkBenderCapFilter::PatchIdArrayName()) : nullptr;
  if (ids && ids->GetNumberOfTuples() > 0)
  {
    const double* range = ids->GetRange(0);
    if (!std::isfinite(range[0]) || !std::isfinite(range[1]) || range[0] < 0.0 ||
      range[1] > static_cast<double>(mesh->GetNumberOfCells()))
    {
      throw StlExportError("the PatchId cell array holds values outside [0, number of cells]");
    }
    const int maxId = static_cast<int>(range[1]);
    for (int k = 1; k <= maxId; ++k)
    {
      names.push_back("cap_" + std::to_string(k));
    }
  }
  return names;
}

namespace
{
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

std::vector<std::string> PlannedStlPaths(vtkPolyData* mesh,
  const std::string& path,
  const StlExportOptions& options)
{
  if (options.patches != StlPatchMode::Files)
  {
    return { path };
  }
  std::vector<std::string> names;
  try
  {
    names = PatchNames(mesh);
  }
  catch (const StlExportError& e)
  {
    throw StlExportError(DisplayName(path) + ": " + e.what());
  }
  std::vector<std::string> paths;
  for (const std::string& name : names)
  {
    paths.push_back(StlStem(path) + "_" + name + ".stl");
  }
  return paths;
}

std::vector<std::string> ExportStl(vtkPolyData* mesh,
  const std::string& path,
  const StlExportOptions& options)
{
  if (!mesh)
  {
    throw StlExportError(DisplayName(path) + ": no mesh to export");
  }
  std::vector<std::string> names;
  std::vector<std::vector<Facet>> facets;
  try
  {
    names = PatchNames(mesh);
    facets =
      Facets(mesh, options.frame, options.patches == StlPatchMode::Single ? 1 : names.size());
  }
  catch (const StlExportError& e)
  {
    throw StlExportError(DisplayName(path) + ": " + e.what());
  }
  const std::string header = Header(options);
  std::vector<std::string> written;
  switch (options.patches)
  {
    case StlPatchMode::Single:
      WriteAll(
        { { path, Producer([&](std::FILE* f) { return WriteBinary(f, header, facets[0]); }) } });
      written.push_back(path);
      break;
    case StlPatchMode::Solids:
      WriteAll({ { path,
        Producer(
          [&](std::FILE* f)
          {
            // ASCII STL has no comment: the header follows the first solid's name on its
            // endsolid line, which readers ignore (OpenFOAM would fold it into the patch name
            // on the solid line).
            bool ok = true;
            for (std::size_t k = 0; k < names.size(); ++k)
            {
              if (facets[k].empty())
              {
                continue;
              }
              ok = ok && WriteSolid(f, names[k], k == 0 ? "  " + header : std::string(), facets[k]);
            }
            return ok;
          }) } });
      written.push_back(path);
      break;
    case StlPatchMode::Files:
    {
      // All patches or none: a case with the wall but without its inlets is worse than none.
      const std::string stem = StlStem(path);
      std::vector<AtomicFile> files;
      for (std::size_t k = 0; k < names.size(); ++k)
      {
        if (facets[k].empty())
        {
          continue;
        }
        const std::string file = stem + "_" + names[k] + ".stl";
        const std::string fileHeader = header + ", patch " + names[k];
        const std::vector<Facet>& patch = facets[k];
        files.push_back({ file,
          Producer(
            [fileHeader, &patch](std::FILE* f) { return WriteBinary(f, fileHeader, patch); }) });
        written.push_back(file);
      }
      WriteAll(files);
      break;
    }
  }
  return written;
}

bool WriteStlFile(vtkPolyData* mesh,
  const std::string& path,
  bool binary,
  const std::string& header,
  std::string& problem)
{
  std::vector<std::vector<Facet>> facets;
  try
  {
    facets = Facets(mesh, StlFrame::LPS, 1);
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
