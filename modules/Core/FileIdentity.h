#ifndef bender_FileIdentity_h
#define bender_FileIdentity_h

#include <string>

namespace bender
{

/// True when both paths name the same existing file (same device and inode: links and other
/// spellings included), or, for paths that do not exist yet, the same path once made absolute
/// and normalised. False when either is empty. Used everywhere an output must never overwrite an
/// input (meshes, plans, recordings and their sidecars).
bool SameFile(const std::string& a, const std::string& b);

/// `path` made absolute and lexically normalised (no file system access beyond the current
/// folder); `path` itself when the current folder cannot be read.
std::string AbsolutePath(const std::string& path);

} // namespace bender

#endif
