#ifndef bender_AtomicFileRecovery_h
#define bender_AtomicFileRecovery_h

// What AtomicWrite and AtomicWriteAll (AtomicFile.h) leave when their process dies in the
// middle (a crash, a kill, a power cut), and how the next writer recovers it. A target is
// always whole, old or new; AtomicWriteAll publishes a set under a journal beside its first
// file, so a writer killed between two renames leaves a set that the next one finishes.

#include <string>

namespace bender
{

/// Cleans up after writers that died in folder (their process no longer runs): a set that
/// AtomicWriteAll was publishing is finished (every file of it was complete on disk before
/// the first was published), and their temporary and kept previous files are removed.
/// AtomicWrite and AtomicWriteAll call it for the folders they write to, so the next write
/// there recovers; a program may also call it when it starts.
void RecoverInterruptedWrites(const std::string& folder);

/// A new empty folder beside target in which to build its replacement ("<parent>/.<name>.tmp-
/// <pid>-<n>"; the leftover of a process that died is removed by RecoverInterruptedWrites,
/// which this calls first for target's parent). Throws std::filesystem::filesystem_error when
/// it cannot be created.
std::string TemporaryFolderBeside(const std::string& target);

/// Puts the folder `built` (from TemporaryFolderBeside, complete) in target's place: renamed
/// over an absent or empty target; a non-empty one is exchanged with it in one step
/// (renameat2 RENAME_EXCHANGE: the target is never missing) and its old content removed.
/// Where the file system cannot exchange, the old target is first renamed aside as
/// ".<name>.previous-<pid>-<n>", which RecoverInterruptedWrites puts back when the process
/// died before built took its place. False with problem set; built is then the caller's to
/// remove.
bool AtomicReplaceFolder(const std::string& built, const std::string& target, std::string& problem);

} // namespace bender

#endif
