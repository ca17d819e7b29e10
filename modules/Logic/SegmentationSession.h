#ifndef bender_SegmentationSession_h
#define bender_SegmentationSession_h

#include "Progress.h"
#include "SurfaceExtraction.h"
#include "VesselSegmentation.h"
#include "Volume.h"
#include "WarpPlan.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <memory>
#include <string>

namespace bender
{

/// For a DICOM folder holding several series: the UID of the largest (most slices; the first
/// by UID among equals) and, in `note`, one sentence saying which was chosen and what else the
/// folder holds. Empty (and no note) for a file, a folder of one series or of none (ReadVolume
/// then reads it or says it holds no DICOM). Throws VolumeReadError for an unreadable folder.
std::string ChooseLargestDicomSeries(const std::string& folder, std::string& note);

/// The DICOM series to read from `path` (what VolumeReadOptions::dicomSeriesUid takes), the one
/// choice of the window's read job and of bender-cli segment. For a folder: `requestedUid` when
/// set, else ChooseLargestDicomSeries (`note` says which, when there was a choice). Throws
/// VolumeReadError, one line naming the folder and listing its series (UID, description,
/// slices), when `requestedUid` names none of them, and for an unreadable folder. For a file
/// (or a missing path) `requestedUid` is returned unchecked: ReadVolume says what is wrong.
std::string ChooseDicomSeries(const std::string& path,
  const std::string& requestedUid,
  std::string& note);

/// The parameters of the Segment panel: the segmentation stage and the surface stage.
struct SegmentationSettings
{
  SegmentationParameters segmentation;
  SurfaceParameters surface;
};

/// The ranges the Segment panel, the session and the session file accept:
/// ValidateSegmentationParameters and a smoothing in [0, 1]. False, and `problem` says why,
/// otherwise. Needs no ITK (SegmentationSettings.cxx).
bool CheckSegmentationSettings(const SegmentationSettings& settings, std::string& problem);

/// The segmentation half of the application state, without Qt: the loaded volume, the mask of
/// the last segmentation, the parameters, and the jobs that read and segment (run on a worker,
/// finished on the session's thread, as BenderSession's jobs). The window shows the volume and
/// the mask; the surface goes to BenderSession.
///
/// Volumes and masks are shared read-only (std::shared_ptr<const ...>): a job holds what it
/// reads, so the window may replace them while a job runs.
class SegmentationSession
{
public:
  /// Reads a volume file or DICOM folder (ReadVolume) on the job's thread. A DICOM folder
  /// holding several series: the series `dicomSeriesUid` when set, else the largest (most
  /// slices; the first by UID among equals), and `note` says which was read and what else the
  /// folder holds.
  struct ReadJob
  {
    std::string path;
    std::string dicomSeriesUid;
    /// Optional: a mask file on the volume's grid (a recovered segmentation), read after it.
    std::string maskPath;
    std::shared_ptr<const Volume> volume;
    /// The mask read from maskPath; null when none was asked or it could not be used.
    std::shared_ptr<const LabelMap> mask;
    /// Why the mask asked for was not read (the volume still is); empty otherwise.
    std::string maskProblem;
    /// The series read from a DICOM folder holding several; empty otherwise.
    std::string seriesRead;
    /// One sentence for the user when a choice was made for them; empty otherwise.
    std::string note;
    /// Throws the reader's errors (bender::Error: a folder with no DICOM series, a missing
    /// file, ...) and bender::Cancelled.
    void Run(const ProgressReporter& progress);
  };

  /// Where the loaded volume came from: the file or DICOM folder (absolute) and the series
  /// read from a folder holding several. An empty path: a volume made here (the demo's).
  struct VolumeSource
  {
    std::string path;
    std::string dicomSeriesUid;
  };

  /// Segments a volume and extracts its surface (SegmentLoadedVolume: SegmentVessels, then
  /// ExtractSurface, then the plausibility rule).
  struct SegmentJob
  {
    std::shared_ptr<const Volume> volume;
    SegmentationSettings settings;
    std::shared_ptr<const LabelMap> mask;
    vtkSmartPointer<vtkPolyData> surface;
    /// SegmentationWarning's sentence when the segmentation kept too little; empty otherwise.
    std::string warning;
    /// Throws the segmentation's errors (bender::Error) and bender::Cancelled.
    void Run(const ProgressReporter& progress);
  };

  /// The built-in demo (DemoPipeline): the MRA-like volume made from the demo vessel, its
  /// segmentation and surface, and the demo plan. Without the segmentation (missing ITK data,
  /// a failure) it falls back to the vessel surface itself and says why in `fallback`.
  struct DemoJob
  {
    std::shared_ptr<const Volume> volume; ///< null in the fallback
    std::shared_ptr<const LabelMap> mask;
    vtkSmartPointer<vtkPolyData> surface;
    WarpPlan plan;
    std::string summary;
    std::string fallback;
    /// Throws bender::Cancelled, and the readers' errors when even the fallback fails.
    void Run(const ProgressReporter& progress);
  };

  bool HasVolume() const { return this->LoadedVolume != nullptr; }
  const std::shared_ptr<const Volume>& GetVolume() const { return this->LoadedVolume; }
  /// The mask of the last segmentation of the loaded volume; null before one.
  const std::shared_ptr<const LabelMap>& GetMask() const { return this->Mask; }
  const std::string& GetVolumeName() const { return this->VolumeName; }
  /// Where the loaded volume was read from (empty without a volume or for one made here).
  const VolumeSource& GetVolumeSource() const { return this->Source; }

  /// Makes `volume` the loaded one (its mask, if any, with it); null unloads. `source`: the
  /// file it was read from, if any.
  void SetVolume(std::shared_ptr<const Volume> volume,
    const std::string& name,
    std::shared_ptr<const LabelMap> mask = nullptr,
    const VolumeSource& source = {});
  /// Forgets the volume and the mask (a mesh was opened instead).
  void Clear();

  /// Validated when set: false, and `problem` says why, for parameters out of range.
  bool SetSettings(const SegmentationSettings& settings, std::string& problem);
  const SegmentationSettings& GetSettings() const { return this->Settings; }

  std::shared_ptr<ReadJob> BeginRead(const std::string& path,
    const std::string& dicomSeriesUid = {}) const;
  /// Takes the job's volume (and mask, if it read one) as the loaded one, named `name`
  /// (empty: the file's name).
  void FinishRead(const ReadJob& job, const std::string& name = {});
  /// Null, and `problem` says why, without a loaded volume.
  std::shared_ptr<SegmentJob> BeginSegment(std::string& problem) const;
  /// Keeps the mask when the job segmented the volume still loaded.
  void FinishSegment(const SegmentJob& job);
  /// Takes the demo's volume and mask (none in the fallback: the loaded volume is dropped).
  void FinishDemo(const DemoJob& job);

private:
  std::shared_ptr<const Volume> LoadedVolume;
  std::shared_ptr<const LabelMap> Mask;
  std::string VolumeName;
  VolumeSource Source;
  SegmentationSettings Settings;
};

} // namespace bender

#endif
