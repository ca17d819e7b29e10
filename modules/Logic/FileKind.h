#ifndef bender_FileKind_h
#define bender_FileKind_h

#include <string>

namespace bender
{

/// What Bender opens a path as. The GUI's Open, Open Recent and drag and drop dispatch on it.
enum class FileKind
{
  Mesh,    ///< a readable format of the mesh-format table (MeshFormats.h): .stl .obj ...
  Volume,  ///< .nrrd .nhdr .nii .nii.gz .mha .mhd .vti, or a folder (a DICOM series)
  Plan,    ///< .bender.json (any other .json too: the plan reader says what is wrong)
  Session, ///< .bender-session.json (an autosave): recovery
  Unknown
};

/// Classifies `path` by its name (case-insensitive); `isDirectory` says the path is a folder.
/// Reads nothing: whether the file is valid is for the reader of its kind to say.
FileKind ClassifyFile(const std::string& path, bool isDirectory = false);

/// "mesh", "volume", "plan", "session" or "unknown".
const char* FileKindName(FileKind kind);

/// The one-line refusal for a file of unknown type, naming it and the kinds Bender reads.
std::string UnknownFileTypeMessage(const std::string& name);

} // namespace bender

#endif
