#include "FileKind.h"

#include "MeshFormats.h"
#include "StringUtil.h"

#include <algorithm>
#include <cstring>
#include <iterator>

namespace bender
{

namespace
{
// A name that ends with suffix and has something before it (".json" alone is no plan).
bool NameEndsWith(const std::string& name, const char* suffix)
{
  return name.size() > std::strlen(suffix) && EndsWith(name, suffix);
}
} // namespace

FileKind ClassifyFile(const std::string& path, bool isDirectory)
{
  if (isDirectory)
  {
    return FileKind::Volume;
  }
  // The name alone: a folder part such as "scans.stl/" must not decide the kind.
  const std::size_t slash = path.find_last_of("/\\");
  const std::string name = ToLower(slash == std::string::npos ? path : path.substr(slash + 1));
  if (NameEndsWith(name, ".bender-session.json"))
  {
    return FileKind::Session;
  }
  if (NameEndsWith(name, ".json"))
  {
    return FileKind::Plan;
  }
  const std::optional<MeshFormat> mesh = FindMeshFormat(name);
  if (mesh && mesh->CanRead())
  {
    return FileKind::Mesh;
  }
  const char* const volumes[] = { ".nrrd", ".nhdr", ".nii", ".nii.gz", ".mha", ".mhd", ".vti" };
  if (std::any_of(std::begin(volumes),
        std::end(volumes),
        [&](const char* ext) { return NameEndsWith(name, ext); }))
  {
    return FileKind::Volume;
  }
  return FileKind::Unknown;
}

const char* FileKindName(FileKind kind)
{
  switch (kind)
  {
    case FileKind::Mesh:
      return "mesh";
    case FileKind::Volume:
      return "volume";
    case FileKind::Plan:
      return "plan";
    case FileKind::Session:
      return "session";
    case FileKind::Unknown:
      break;
  }
  return "unknown";
}

std::string UnknownFileTypeMessage(const std::string& name)
{
  std::string meshes;
  for (const std::string& ext : MeshExtensions(MeshAccess::Read))
  {
    meshes += (meshes.empty() ? "" : " ") + ext.substr(1);
  }
  return name + ": unknown file type (meshes: " + meshes +
    "; volumes: nrrd nhdr nii nii.gz mha mhd vti or a DICOM folder; plans: .bender.json; "
    "sessions: .bender-session.json)";
}

} // namespace bender
