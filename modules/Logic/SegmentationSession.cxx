#include "SegmentationSession.h"

#include "DemoPipeline.h"
#include "MeshIO.h"
#include "SegmentVolume.h"
#include "VolumeIO.h"
#include "WarpPlanIO.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <sstream>
#include <system_error>

namespace bender
{

std::string ChooseLargestDicomSeries(const std::string& folder, std::string& note)
{
  note.clear();
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec))
  {
    return {};
  }
  const std::vector<DicomSeriesInfo> series = ListDicomSeries(folder);
  if (series.size() < 2)
  {
    return {};
  }
  // The most slices; the first by UID among equals (ListDicomSeries sorts by UID).
  const auto largest = std::max_element(series.begin(),
    series.end(),
    [](const DicomSeriesInfo& a, const DicomSeriesInfo& b) { return a.sliceCount < b.sliceCount; });
  std::filesystem::path name = std::filesystem::path(folder).lexically_normal();
  if (name.filename().empty() && name.has_parent_path())
  {
    name = name.parent_path();
  }
  std::ostringstream text;
  text << name.filename().string() << ": " << series.size()
       << " DICOM series in this folder; read the largest, "
       << (largest->description.empty() ? std::string("(no description)")
                                        : "\"" + largest->description + "\"")
       << " (" << largest->sliceCount << " slices, UID " << largest->uid << "); the others:";
  for (const DicomSeriesInfo& other : series)
  {
    if (other.uid != largest->uid)
    {
      text << " " << (other.description.empty() ? other.uid : other.description) << " ("
           << other.sliceCount << " slices)";
    }
  }
  note = text.str();
  return largest->uid;
}

std::string ChooseDicomSeries(const std::string& path,
  const std::string& requestedUid,
  std::string& note)
{
  note.clear();
  if (requestedUid.empty())
  {
    return ChooseLargestDicomSeries(path, note);
  }
  std::error_code ec;
  if (!std::filesystem::is_directory(path, ec))
  {
    return requestedUid;
  }
  const std::vector<DicomSeriesInfo> series = ListDicomSeries(path);
  if (std::any_of(series.begin(),
        series.end(),
        [&](const DicomSeriesInfo& s) { return s.uid == requestedUid; }))
  {
    return requestedUid;
  }
  std::ostringstream text;
  text << path << ": no DICOM series with UID " << requestedUid;
  if (series.empty())
  {
    text << " (the folder holds no DICOM series)";
  }
  else
  {
    text << "; the folder holds " << series.size() << ":";
    for (const DicomSeriesInfo& s : series)
    {
      text << " [" << s.uid << " \"" << s.description << "\" " << s.sliceCount << " slices]";
    }
  }
  throw VolumeReadError(text.str());
}

void SegmentationSession::ReadJob::Run(const ProgressReporter& progress)
{
  VolumeReadOptions options;
  // The series asked for (a recovered session's), else a folder with several series: the
  // largest, and the user is told which.
  options.dicomSeriesUid = ChooseDicomSeries(this->path, this->dicomSeriesUid, this->note);
  this->volume = std::make_shared<const Volume>(ReadVolume(this->path, options, progress));
  this->seriesRead = options.dicomSeriesUid;
  if (this->maskPath.empty())
  {
    return;
  }
  // The mask: its own problems never cost the volume.
  try
  {
    const Volume labels = ReadVolume(this->maskPath, {}, progress);
    const ImageGeometry& a = labels.geometry;
    const ImageGeometry& b = this->volume->geometry;
    bool same = a.size == b.size;
    for (std::size_t i = 0; i < 3 && same; ++i)
    {
      const double scale = std::max({ 1.0, std::abs(a.spacing[i]), std::abs(a.origin[i]) });
      same = std::abs(a.spacing[i] - b.spacing[i]) <= 1e-6 * scale &&
        std::abs(a.origin[i] - b.origin[i]) <= 1e-6 * scale;
    }
    if (!same)
    {
      this->maskProblem = std::filesystem::path(this->maskPath).filename().string() +
        ": the mask is not on the volume's grid";
      return;
    }
    auto mask = std::make_shared<LabelMap>();
    mask->geometry = b;
    mask->voxels.resize(labels.voxels.size());
    std::transform(labels.voxels.begin(),
      labels.voxels.end(),
      mask->voxels.begin(),
      [](float v) -> std::uint8_t {
        return std::isfinite(v) ? static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L))
                                : 0;
      });
    this->mask = std::move(mask);
  }
  catch (const Cancelled&)
  {
    throw;
  }
  catch (const std::exception& e) // the volume reader's errors and ITK's: the mask is left out
  {
    this->maskProblem = e.what();
  }
}

void SegmentationSession::SegmentJob::Run(const ProgressReporter& progress)
{
  SegmentVolumeResult result = SegmentLoadedVolume(
    *this->volume, this->settings.segmentation, this->settings.surface, progress);
  this->mask = result.mask;
  this->surface = result.surface;
  this->warning = result.warning;
}

void SegmentationSession::DemoJob::Run(const ProgressReporter& progress)
{
  DemoVessel demo = SegmentDemoVesselOrFallBack(DemoVesselPath(), {}, progress);
  this->fallback = demo.fallback;
  this->plan = ReadWarpPlan(DemoPlanPath());
  if (!demo.volume.voxels.empty())
  {
    this->volume = std::make_shared<const Volume>(std::move(demo.volume));
    this->mask = std::make_shared<const LabelMap>(std::move(demo.mask));
  }
  this->surface = demo.surface;
  this->summary = demo.summary;
}

void SegmentationSession::FinishDemo(const DemoJob& job)
{
  this->SetVolume(job.volume, "demo MRA volume", job.mask);
}

void SegmentationSession::SetVolume(std::shared_ptr<const Volume> volume,
  const std::string& name,
  std::shared_ptr<const LabelMap> mask,
  const VolumeSource& source)
{
  this->LoadedVolume = std::move(volume);
  this->Mask = this->LoadedVolume ? std::move(mask) : nullptr;
  this->VolumeName = this->LoadedVolume ? name : std::string();
  this->Source = this->LoadedVolume ? source : VolumeSource{};
}

void SegmentationSession::Clear()
{
  this->SetVolume(nullptr, {});
}

bool SegmentationSession::SetSettings(const SegmentationSettings& settings, std::string& problem)
{
  if (!CheckSegmentationSettings(settings, problem))
  {
    return false;
  }
  this->Settings = settings;
  return true;
}

std::shared_ptr<SegmentationSession::ReadJob> SegmentationSession::BeginRead(
  const std::string& path,
  const std::string& dicomSeriesUid) const
{
  auto job = std::make_shared<ReadJob>();
  job->path = path;
  job->dicomSeriesUid = dicomSeriesUid;
  return job;
}

void SegmentationSession::FinishRead(const ReadJob& job, const std::string& name)
{
  if (!job.volume)
  {
    return;
  }
  std::filesystem::path file = std::filesystem::path(job.path).lexically_normal();
  if (file.filename().empty() && file.has_parent_path())
  {
    file = file.parent_path(); // "folder/"
  }
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(file, ec);
  VolumeSource source;
  source.path = ec ? file.string() : absolute.string();
  source.dicomSeriesUid = job.seriesRead;
  this->SetVolume(job.volume, name.empty() ? file.filename().string() : name, job.mask, source);
}

std::shared_ptr<SegmentationSession::SegmentJob> SegmentationSession::BeginSegment(
  std::string& problem) const
{
  if (!this->LoadedVolume)
  {
    problem = "Segment: open a volume first";
    return nullptr;
  }
  auto job = std::make_shared<SegmentJob>();
  job->volume = this->LoadedVolume;
  job->settings = this->Settings;
  return job;
}

void SegmentationSession::FinishSegment(const SegmentJob& job)
{
  if (job.volume == this->LoadedVolume)
  {
    this->Mask = job.mask;
  }
}

} // namespace bender
