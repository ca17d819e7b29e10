#include "FileKind.h"

#include <algorithm>
#include <cctype>
#include <initializer_list>

namespace bender
{

namespace
{
std::string Lower(const std::string& text)
{
  std::string lower = text;
  std::transform(lower.begin(),
    lower.end(),
    lower.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower;
}

bool EndsWith(const std::string& text, const std::string& suffix)
{
  return text.size() > suffix.size() &&
    text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool EndsWithAny(const std::string& text, std::initializer_list<const char*> suffixes)
{
  return std::any_of(
    suffixes.begin(), suffixes.end(), [&](const char* s) { return EndsWith(text, s); });
}
}

FileKind ClassifyFile(const std::string& path, bool isDirectory)
{
  if (isDirectory)
  {
    return FileKind::Volume;
  }
  // The name alone: a folder part such as "scans.stl/" must not decide the kind.
  const std::size_t slash = path.find_last_of("/\\");
  const std::string name = Lower(slash == std::string::npos ? path : path.substr(slash + 1));
  if (EndsWith(name, ".bender-session.json"))
  {
    return FileKind::Session;
  }
  if (EndsWith(name, ".json"))
  {
    return FileKind::Plan;
  }
  if (EndsWithAny(name, { ".stl", ".obj", ".ply", ".vtp", ".vtk", ".off" }))
  {
    return FileKind::Mesh;
  }
  if (EndsWithAny(name, { ".nrrd", ".nhdr", ".nii", ".nii.gz", ".mha", ".mhd", ".vti" }))
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
  return name +
    ": unknown file type (meshes: stl obj ply vtp vtk off; volumes: nrrd nhdr nii nii.gz mha mhd "
    "vti or a DICOM folder; plans: .bender.json; sessions: .bender-session.json)";
}

} // namespace bender
