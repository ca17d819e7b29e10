#include "MeshFormats.h"

#include "MeshReaders.h"
#include "MeshWriters.h"
#include "StringUtil.h"
#include "TetgenReader.h"

#include <algorithm>
#include <mutex>
#include <stdexcept>
#include <utility>

namespace bender
{

namespace
{

// The built-in formats, in the order lists show them.
std::vector<MeshFormat> BuiltInFormats()
{
  using namespace io_detail;
  constexpr MeshPrecision Float = MeshPrecision::Float;
  constexpr MeshPrecision Double = MeshPrecision::Double;
  // clang-format off
  // name     extensions   label                                  read               write               named  labels region precision encoding
  return {
    { "stl",   { ".stl" },   "STL",                                ReadStlMesh,       WriteStlMesh,       true,  false, false, Float,  true },
    { "obj",   { ".obj" },   "Wavefront OBJ",                      ReadObjMesh,       WriteObjMesh,       false, false, false, Float,  false },
    { "ply",   { ".ply" },   "PLY",                                ReadPlyMesh,       WritePlyMesh,       false, false, false, Float,  false },
    { "vtp",   { ".vtp" },   "VTK XML polydata with patch labels", ReadVtpMesh,       WriteVtpMesh,       false, true,  false, Double, false },
    { "vtk",   { ".vtk" },   "Legacy VTK polydata",                ReadLegacyVtkMesh, WriteLegacyVtkMesh, false, true,  false, Double, false },
    { "off",   { ".off" },   "OFF",                                ReadOffMesh,       WriteOffMesh,       false, false, false, Double, false },
    { "smesh", { ".smesh" }, "TetGen surface mesh",                ReadTetgenMesh,    WriteSmeshMesh,     false, false, true,  Double, false },
    { "poly",  { ".poly" },  "TetGen piecewise linear complex",    ReadTetgenMesh,    WritePolyMesh,      false, false, true,  Double, false },
  };
  // clang-format on
}

struct Registry
{
  std::mutex mutex;
  std::vector<MeshFormat> rows = BuiltInFormats();
};

Registry& TheRegistry()
{
  static Registry registry;
  return registry;
}

bool HasExtension(const MeshFormat& format, const std::string& ext)
{
  return std::find(format.extensions.begin(), format.extensions.end(), ext) !=
    format.extensions.end();
}

std::string Patterns(const std::vector<std::string>& extensions)
{
  std::string patterns;
  for (const std::string& ext : extensions)
  {
    patterns += (patterns.empty() ? "*" : " *") + ext;
  }
  return patterns;
}

// The extensions of the rows that satisfy `keep`, for a sentence: ".vtp, .smesh and .poly".
template<typename Predicate>
std::string ExtensionsWhere(Predicate keep)
{
  std::vector<std::string> extensions;
  for (const MeshFormat& format : MeshFormats())
  {
    if (keep(format))
    {
      extensions.insert(extensions.end(), format.extensions.begin(), format.extensions.end());
    }
  }
  std::string sentence;
  for (std::size_t i = 0; i < extensions.size(); ++i)
  {
    sentence += (i == 0 ? "" : (i + 1 == extensions.size() ? " and " : ", ")) + extensions[i];
  }
  return sentence;
}

} // namespace

std::vector<MeshFormat> MeshFormats()
{
  Registry& registry = TheRegistry();
  const std::lock_guard<std::mutex> lock(registry.mutex);
  return registry.rows;
}

std::optional<MeshFormat> FindMeshFormat(const std::string& path)
{
  const std::string ext = LowerExtension(path);
  if (ext.empty())
  {
    return std::nullopt;
  }
  for (const MeshFormat& format : MeshFormats())
  {
    if (HasExtension(format, ext))
    {
      return format;
    }
  }
  return std::nullopt;
}

std::optional<MeshFormat> FindMeshFormatByName(const std::string& name)
{
  for (const MeshFormat& format : MeshFormats())
  {
    if (EqualsIgnoreCase(format.name, name))
    {
      return format;
    }
  }
  return std::nullopt;
}

std::vector<std::string> MeshExtensions(MeshAccess access)
{
  std::vector<std::string> extensions;
  for (const MeshFormat& format : MeshFormats())
  {
    if (format.Can(access))
    {
      extensions.insert(extensions.end(), format.extensions.begin(), format.extensions.end());
    }
  }
  return extensions;
}

std::string MeshExtensionList(MeshAccess access, const std::string& separator)
{
  std::string list;
  for (const std::string& ext : MeshExtensions(access))
  {
    list += (list.empty() ? "" : separator) + ext;
  }
  return list;
}

std::string MeshFilesFilter(MeshAccess access, const std::string& title)
{
  return title + " (" + Patterns(MeshExtensions(access)) + ")";
}

std::vector<std::string> MeshFormatFilters(MeshAccess access)
{
  std::vector<std::string> filters;
  for (const MeshFormat& format : MeshFormats())
  {
    if (format.Can(access))
    {
      filters.push_back(format.label + " (" + Patterns(format.extensions) + ")");
    }
  }
  return filters;
}

std::string MeshFileDialogFilters(MeshAccess access)
{
  std::string filters = access == MeshAccess::Read ? MeshFilesFilter(access) : std::string();
  for (const std::string& filter : MeshFormatFilters(access))
  {
    filters += (filters.empty() ? "" : ";;") + filter;
  }
  return filters;
}

void RegisterMeshFormat(MeshFormat format)
{
  if (format.name.empty() || format.label.empty() || format.extensions.empty())
  {
    throw std::invalid_argument("mesh format: a name, a label and an extension are required");
  }
  if (!format.CanRead() && !format.CanWrite())
  {
    throw std::invalid_argument("mesh format " + format.name + ": neither a reader nor a writer");
  }
  for (const std::string& ext : format.extensions)
  {
    if (ext.size() < 2 || ext[0] != '.' || ToLower(ext) != ext)
    {
      throw std::invalid_argument(
        "mesh format " + format.name + ": extension '" + ext + "' is not lower case with a dot");
    }
  }
  Registry& registry = TheRegistry();
  const std::lock_guard<std::mutex> lock(registry.mutex);
  for (const MeshFormat& row : registry.rows)
  {
    if (EqualsIgnoreCase(row.name, format.name))
    {
      throw std::invalid_argument("mesh format " + format.name + ": already registered");
    }
    for (const std::string& ext : format.extensions)
    {
      if (HasExtension(row, ext))
      {
        throw std::invalid_argument(
          "mesh format " + format.name + ": " + ext + " is already " + row.name + "'s");
      }
    }
  }
  registry.rows.push_back(std::move(format));
}

bool UnregisterMeshFormat(const std::string& name)
{
  Registry& registry = TheRegistry();
  const std::lock_guard<std::mutex> lock(registry.mutex);
  const auto row = std::find_if(registry.rows.begin(),
    registry.rows.end(),
    [&](const MeshFormat& format) { return EqualsIgnoreCase(format.name, name); });
  if (row == registry.rows.end())
  {
    return false;
  }
  registry.rows.erase(row);
  return true;
}

ScopedMeshFormat::ScopedMeshFormat(MeshFormat format)
  : Name(format.name)
{
  RegisterMeshFormat(std::move(format));
}

ScopedMeshFormat::~ScopedMeshFormat()
{
  UnregisterMeshFormat(this->Name);
}

MeshExportRules ResolveMeshExport(const MeshFormat& format, const MeshExportRequest& request)
{
  MeshExportRules rules;
  rules.encoding = request.encoding;
  rules.patches = request.patches;
  if (request.patches != StlPatchMode::Single && !format.namedPatches)
  {
    rules.problem = "patches (solids, files) are written as " +
      ExtensionsWhere([](const MeshFormat& f) { return f.namedPatches && f.CanWrite(); }) +
      " only; " +
      ExtensionsWhere(
        [](const MeshFormat& f) { return (f.patchLabels || f.regionPoint) && f.CanWrite(); }) +
      " keep them as labels";
    return rules;
  }
  if (format.namedPatches && request.patches == StlPatchMode::Solids)
  {
    rules.encoding = StlEncoding::Ascii;
  }
  if (format.namedPatches && request.patches == StlPatchMode::Single &&
    request.encoding == StlEncoding::Ascii)
  {
    rules.patches = StlPatchMode::Solids;
  }
  switch (request.sidecar)
  {
    case SidecarChoice::On:
      rules.sidecar = true;
      break;
    case SidecarChoice::Off:
      rules.sidecar = false;
      break;
    case SidecarChoice::Auto:
      rules.sidecar = request.patches != StlPatchMode::Single || format.regionPoint;
      break;
  }
  rules.measure = rules.sidecar || format.regionPoint;
  return rules;
}

} // namespace bender
