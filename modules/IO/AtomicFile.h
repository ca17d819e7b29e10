#ifndef bender_AtomicFile_h
#define bender_AtomicFile_h

// The project's one way to write a file so that readers never see it half-written: every
// writer of meshes, plans, sessions, STL exports and rendered images goes through here.

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace bender
{

/// Writes the whole content of a file to tempPath (a fresh file name in the target's
/// folder, with the target's extension last, so writers that look at it still work).
/// Returns false with problem set (or throws) to abandon the write.
using FileProducer = std::function<bool(const std::string& tempPath, std::string& problem)>;

/// Writes path atomically: produce(tempPath) writes the content to a unique temporary file in
/// the target's folder (same file system), which is flushed to disk (fsync) and renamed over
/// path. On any failure the temporary file is removed and nothing at path changes.
/// Returns false with problem set to a short description without the file name ("folder out
/// does not exist", "is a folder, not a file", ...; left as produce set it when produce
/// fails, "write failed" when it set nothing). Exceptions thrown by produce propagate after
/// the temporary file is removed.
bool AtomicWrite(const std::string& path, const FileProducer& produce, std::string& problem);

/// A producer that writes `text` as the whole content of its temporary file ("cannot create a
/// file there", "write failed (disk full?)").
FileProducer TextProducer(std::shared_ptr<const std::string> text);

/// Writes text as the whole content of path through AtomicWrite.
bool AtomicWriteText(const std::string& path, const std::string& text, std::string& problem);

/// One file of a set written by AtomicWriteAll.
struct AtomicFile
{
  std::string path;
  FileProducer produce;
};

/// Writes a set of files all-or-nothing (a multi-file export: one STL per patch): every file
/// is first written to its temporary and flushed; only when all are complete are they renamed
/// over their targets. When a rename fails part-way, the targets already replaced are put back
/// (the previous files are kept as hard links until every rename succeeded) and the targets
/// that did not exist are removed, so on failure the folder holds what it held before.
/// Returns false with problem set to "<file base name>: <problem>" for the first file that
/// failed; refuses an empty set and the same target named twice. Exceptions thrown by a
/// producer propagate after every temporary file is removed.
bool AtomicWriteAll(const std::vector<AtomicFile>& files, std::string& problem);

} // namespace bender

#endif
