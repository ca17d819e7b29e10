#include "SegmentationSession.h"

#include "DemoPipeline.h"
#include "MeshIO.h"
#include "VolumeIO.h"
#include "WarpPlanIO.h"

#include <exception>

namespace bender
{

void SegmentationSession::ReadJob::Run(const ProgressReporter& progress)
{
  this->volume = std::make_shared<const Volume>(ReadVolume(this->path, {}, progress));
}

void SegmentationSession::SegmentJob::Run(const ProgressReporter& progress)
{
  auto labels = std::make_shared<const LabelMap>(
    SegmentVessels(*this->volume, this->settings.segmentation, progress));
  SurfaceResult result = ExtractSurface(*labels, this->settings.surface, progress);
  this->mask = labels;
  this->surface = result.surface;
}

void SegmentationSession::DemoJob::Run(const ProgressReporter& progress)
{
  DemoVessel demo;
  try
  {
    demo = SegmentDemoVessel(DemoVesselPath(), {}, progress);
  }
  catch (const Cancelled&)
  {
    throw;
  }
  catch (const std::exception& e)
  {
    // Without the segmentation the demo still bends the vessel surface itself.
    this->fallback = e.what();
    demo.surface = ReadMesh(DemoVesselPath());
  }
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
  std::shared_ptr<const LabelMap> mask)
{
  this->LoadedVolume = std::move(volume);
  this->Mask = this->LoadedVolume ? std::move(mask) : nullptr;
  this->VolumeName = this->LoadedVolume ? name : std::string();
}

void SegmentationSession::Clear()
{
  this->SetVolume(nullptr, {});
}

bool SegmentationSession::SetSettings(const SegmentationSettings& settings, std::string& problem)
{
  try
  {
    ValidateSegmentationParameters(settings.segmentation);
  }
  catch (const std::exception& e)
  {
    problem = e.what();
    return false;
  }
  if (!(settings.surface.smoothing >= 0.0 && settings.surface.smoothing <= 1.0))
  {
    problem = "smoothing: must be in [0, 1]";
    return false;
  }
  this->Settings = settings;
  return true;
}

std::shared_ptr<SegmentationSession::ReadJob> SegmentationSession::BeginRead(
  const std::string& path) const
{
  auto job = std::make_shared<ReadJob>();
  job->path = path;
  return job;
}

void SegmentationSession::FinishRead(const ReadJob& job)
{
  this->SetVolume(job.volume, job.path);
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
