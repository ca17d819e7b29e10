#ifndef bender_SessionAutosave_h
#define bender_SessionAutosave_h

#include "BenderErrors.h"
#include "SegmentationSession.h"
#include "Volume.h"
#include "WarpPlan.h"

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace bender
{

/// A session file cannot be read or written; what() names the file and the problem.
class SessionFileError : public InputError
{
public:
  using InputError::InputError;
};

/// The volume behind the session's surface: where it was read from and what it was, so that
/// recovery reads it again and can tell whether the file found there is still the same volume.
struct SessionVolume
{
  /// Absolute path of the volume file or DICOM folder.
  std::string path;
  /// The volume's name in the window; empty: the file's name.
  std::string name;
  /// The series read from a DICOM folder holding several; empty otherwise.
  std::string dicomSeriesUid;
  /// Size, spacing, origin and direction: the volume's identity (SameVolumeGeometry).
  ImageGeometry geometry;
  /// The mask of its segmentation (the slice views' overlay), a file kept beside the autosave;
  /// empty when there is none.
  std::string maskPath;
};

/// The ribbon lying on the surface and the Bend parameters it was placed with.
struct SessionRibbon
{
  RibbonSpec ribbon;
  double radius = 10.0; ///< R of the next warp, model units, > 0
  DecaySpec decay;
  /// The radius of the vessel the ribbon was placed on (the handles' size); 0: unknown.
  double vesselRadius = 0.0;
};

/// What an autosave keeps so that a crash loses nothing: a reference to the source surface (a
/// mesh file; a segmented surface is saved beside the autosave file first), the surface's
/// name, the plan committed so far and, when the window has them, the volume, the
/// segmentation parameters and the placed ribbon.
///
/// JSON, version 2: {"format": "bender-session", "version": 2, "source": PATH, "name": NAME,
/// "frame": "LPS", "plan": {warp-file-format.md object}, "volume": {"path", "name", "series",
/// "size": [3], "spacing": [3], "origin": [3], "direction": [9], "mask"}, "segmentation":
/// {every SegmentationParameters and SurfaceParameters field by name}, "ribbon": {"start",
/// "end": {"position", "tangent", "normal"}, "extraTurns", "radius", "decay", "plateau",
/// "vesselRadius"}}. "name", "volume" (and its "series" and "mask"), "segmentation" and
/// "ribbon" are optional. Version 1 files (source, name, frame, plan) are still read.
struct SessionSnapshot
{
  std::string sourcePath; ///< absolute path of the surface the plan applies to
  /// The surface's name in the window ("demo vessel (segmented)", "aneurysm.stl"); optional
  /// ("name" in the file), empty when unknown.
  std::string surfaceName;
  std::string frame = "LPS";
  WarpPlan plan;
  std::optional<SessionVolume> volume;
  std::optional<SegmentationSettings> segmentation;
  std::optional<SessionRibbon> ribbon;
};

/// The version WriteSessionFile writes.
constexpr int SessionFileVersion = 2;

/// Writes atomically (temporary file in the same folder, then rename); creates the folder.
/// Throws SessionFileError (a non-finite number, an unwritable folder).
void WriteSessionFile(const SessionSnapshot& snapshot, const std::string& path);

/// Reads and validates (the plan as ReadWarpPlan would, the segmentation parameters as
/// ValidateSegmentationParameters). Throws SessionFileError naming the file and the field.
SessionSnapshot ReadSessionFile(const std::string& path);

/// True when `a` and `b` are the same grid: equal sizes, spacing and origin within 1e-6 of the
/// larger magnitude (at least 1e-6 mm), direction within 1e-6.
bool SameVolumeGeometry(const ImageGeometry& a, const ImageGeometry& b);

/// "256x256x130 voxels of 0.9x0.9x1.2 mm" for messages.
std::string DescribeVolumeGeometry(const ImageGeometry& geometry);

/// Where the window keeps a volume that has no file (the demo's) beside the autosave
/// `sessionPath`.
std::string SessionVolumeCopyPath(const std::string& sessionPath);

/// Where the window keeps the mask of the volume's segmentation beside the autosave.
std::string SessionMaskCopyPath(const std::string& sessionPath);

/// The files an autosave keeps beside itself for data that has no file of its own (the demo's
/// volume, a segmentation's mask), written on a thread of their own so that the caller (the
/// window's GUI thread, inside an autosave) never waits for a volume to be written. A copy is
/// referenced only once it is complete: CopyOf returns its path only when the file there was
/// written in full from that very object (the writers write all-or-nothing, a staging file
/// renamed into place, so the file at the path is always a complete copy of some object);
/// meanwhile the caller's autosave leaves it out and `finished`, called when the write ends,
/// tells the owner to autosave again.
///
/// One write at a time per path: asked for another object while one is written, CopyOf starts
/// nothing, and the next call after `finished` starts it. A failed write is reported once (in
/// `problem`) and not retried for the same object.
class AutosaveCopies
{
public:
  /// Writes `object` to the path given (throws on failure); runs on the copies' thread.
  using WriteFunction = std::function<void(const std::string& path)>;

  /// `finished` runs on the writing thread after each write, complete or failed; it must not
  /// call back into this object (the window posts an autosave to its own thread).
  explicit AutosaveCopies(std::function<void()> finished = {});
  /// Waits for the writes under way.
  ~AutosaveCopies();
  AutosaveCopies(const AutosaveCopies&) = delete;
  AutosaveCopies& operator=(const AutosaveCopies&) = delete;

  /// `path` when the file there is a complete copy of `object`; empty otherwise, after starting
  /// to write it with `write` when no write to `path` is under way (and it has not failed for
  /// this object). `problem`: why the last write of `object` failed, said once; else empty.
  std::string CopyOf(const std::shared_ptr<const void>& object,
    const std::string& path,
    const WriteFunction& write,
    std::string& problem);

  /// True while a write is under way.
  bool IsWriting() const;

  /// Waits for the writes under way (closing the window; tests): their files are complete or
  /// absent afterwards, and `finished` has run.
  void Wait();

  /// Waits, then forgets what was written (the autosave and its copies are discarded).
  void Forget();

private:
  struct Slot
  {
    std::weak_ptr<const void> written;
    std::weak_ptr<const void> failed;
    std::shared_ptr<const void> writing;
    std::string problem;
    std::thread thread;
  };
  void Run(Slot* slot, std::string path, std::shared_ptr<const void> object, WriteFunction write);

  std::function<void()> Finished;
  mutable std::mutex Mutex;
  std::map<std::string, Slot> Slots;
};

/// Removes the files the window keeps beside the autosave `sessionPath` (the volume and mask
/// copies); the
/// session file itself and the surface copy are BenderSession::DiscardAutosave's.
void RemoveSessionSideFiles(const std::string& sessionPath);

} // namespace bender

#endif
