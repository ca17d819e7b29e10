#include "VolumeIO.h"

#include "AtomicFile.h"
#include "InputValidation.h"
#include "ItkVtkBridge.h"
#include "Private/ItkImage.h"
#include "StringUtil.h"
#include "VolumeValidation.h"

#include <itkGDCMImageIO.h>
#include <itkGDCMImageIOFactory.h>
#include <itkGDCMSeriesFileNames.h>
#include <itkImageFileReader.h>
#include <itkImageFileWriter.h>
#include <itkImageSeriesReader.h>
#include <itkMetaImageIO.h>
#include <itkMetaImageIOFactory.h>
#include <itkNiftiImageIO.h>
#include <itkNiftiImageIOFactory.h>
#include <itkNrrdImageIO.h>
#include <itkNrrdImageIOFactory.h>

#include <vtkCallbackCommand.h>
#include <vtkDataArray.h>
#include <vtkErrorCode.h>
#include <vtkExecutive.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLImageDataWriter.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <mutex>
#include <random>
#include <sstream>

#include <unistd.h>

namespace bender
{
namespace
{

using detail::FloatImage;
using detail::MaskImage;

enum class VolumeFormat
{
  Nrrd,
  Nifti,
  Meta,
  Vti,
  Unknown
};

VolumeFormat FormatOf(const std::string& path)
{
  const std::string p = ToLower(path);
  if (EndsWith(p, ".nrrd") || EndsWith(p, ".nhdr"))
  {
    return VolumeFormat::Nrrd;
  }
  if (EndsWith(p, ".nii") || EndsWith(p, ".nii.gz"))
  {
    return VolumeFormat::Nifti;
  }
  if (EndsWith(p, ".mha") || EndsWith(p, ".mhd"))
  {
    return VolumeFormat::Meta;
  }
  if (EndsWith(p, ".vti"))
  {
    return VolumeFormat::Vti;
  }
  return VolumeFormat::Unknown;
}

itk::ImageIOBase::Pointer MakeImageIO(VolumeFormat format)
{
  switch (format)
  {
    case VolumeFormat::Nrrd:
      return itk::NrrdImageIO::New().GetPointer();
    case VolumeFormat::Nifti:
      return itk::NiftiImageIO::New().GetPointer();
    case VolumeFormat::Meta:
      return itk::MetaImageIO::New().GetPointer();
    default:
      return nullptr;
  }
}

/// ITK messages span several lines, start with the source location and object address, may
/// hold teem's "[nrrd]" chains, ANSI colours or file bytes: one clean line of the description.
std::string OneLine(const itk::ExceptionObject& e)
{
  return io_detail::CleanMessage(e.GetDescription() ? e.GetDescription() : "", 240);
}

/// The readers also work through ITK's factories (e.g. GDCM inside ImageSeriesReader): register
/// them explicitly so that a static library linked into any executable finds them.
void RegisterImageIOFactories()
{
  static std::once_flag once;
  std::call_once(once,
    []
    {
      // Problems reach the user as exceptions; ITK's own warnings would only be noise on stderr.
      itk::Object::GlobalWarningDisplayOff();
      itk::NrrdImageIOFactory::RegisterOneFactory();
      itk::NiftiImageIOFactory::RegisterOneFactory();
      itk::MetaImageIOFactory::RegisterOneFactory();
      itk::GDCMImageIOFactory::RegisterOneFactory();
    });
}

void CheckGeometry(const ImageGeometry& g, const std::string& path)
{
  for (int c = 0; c < 3; ++c)
  {
    if (!(std::isfinite(g.spacing[c]) && g.spacing[c] > 0.0))
    {
      std::ostringstream msg;
      msg << path << ": invalid voxel spacing " << g.spacing[c] << " along axis " << c
          << " (must be > 0 mm)";
      throw VolumeReadError(msg.str());
    }
    if (!std::isfinite(g.origin[c]))
    {
      throw VolumeReadError(path + ": non-finite origin");
    }
    if (g.size[c] == 0)
    {
      throw VolumeReadError(path + ": volume has no voxels");
    }
  }
  for (double d : g.direction)
  {
    if (!std::isfinite(d))
    {
      throw VolumeReadError(path + ": non-finite direction matrix");
    }
  }
  // The direction's columns are the index axes in LPS: unit length and mutually orthogonal
  // (a scaled or sheared matrix, such as a TransformMatrix of 1e308, would put the surface at
  // absurd or infinite coordinates that only the output writer would then notice).
  for (int a = 0; a < 3; ++a)
  {
    for (int b = a; b < 3; ++b)
    {
      double dot = 0.0;
      for (int r = 0; r < 3; ++r)
      {
        dot += g.direction[3 * r + a] * g.direction[3 * r + b];
      }
      if (!(std::abs(dot - (a == b ? 1.0 : 0.0)) < 1e-3))
      {
        throw VolumeReadError(path + ": the direction matrix is not a rotation (columns " +
          (a == b ? "of unit length" : "orthogonal") + " expected)");
      }
    }
  }
  // The volume must lie within a kilometre of the scanner's origin: beyond that the header is
  // wrong (and single-precision surface coordinates would lose their millimetres).
  constexpr double MaxExtentMm = 1.0e6;
  for (int c = 0; c < 3; ++c)
  {
    const double reach = std::abs(g.origin[c]) + g.spacing[c] * static_cast<double>(g.size[c]);
    if (!(reach < MaxExtentMm))
    {
      throw VolumeReadError(path + ": the volume reaches beyond 1 km from the origin (spacing " +
        "or origin in the header out of range)");
    }
  }
}

Volume FromItk(const FloatImage* image)
{
  Volume v;
  v.geometry = detail::GetItkGeometry(image);
  detail::CopyBuffer(image, v.voxels);
  return v;
}

Volume ReadItkFile(const std::string& path, VolumeFormat format, const ProgressReporter& progress)
{
  auto io = MakeImageIO(format);
  io->SetFileName(path);
  io->ReadImageInformation();
  if (io->GetPixelType() != itk::IOPixelEnum::SCALAR || io->GetNumberOfComponents() != 1)
  {
    throw VolumeReadError(path + ": pixel type '" +
      itk::ImageIOBase::GetPixelTypeAsString(io->GetPixelType()) + "' with " +
      std::to_string(io->GetNumberOfComponents()) +
      " components is not supported (scalar volumes only)");
  }
  if (io->GetComponentType() == itk::IOComponentEnum::UNKNOWNCOMPONENTTYPE)
  {
    throw VolumeReadError(path + ": unknown voxel component type");
  }
  if (io->GetNumberOfDimensions() < 2 || io->GetNumberOfDimensions() > 3)
  {
    throw VolumeReadError(path + ": " + std::to_string(io->GetNumberOfDimensions()) +
      "-D image, expected a 3-D volume (or a 2-D slice)");
  }
  for (unsigned d = 0; d < io->GetNumberOfDimensions(); ++d)
  {
    if (!(io->GetSpacing(d) > 0.0) || !std::isfinite(io->GetSpacing(d)))
    {
      std::ostringstream msg;
      msg << path << ": invalid voxel spacing " << io->GetSpacing(d) << " along axis " << d
          << " (must be > 0 mm)";
      throw VolumeReadError(msg.str());
    }
  }
  using ReaderType = itk::ImageFileReader<FloatImage>;
  auto reader = ReaderType::New();
  reader->SetFileName(path);
  reader->SetImageIO(io);
  detail::WatchFilter(reader, progress, "read");
  reader->Update();
  return FromItk(reader->GetOutput());
}

Volume ReadVti(const std::string& path)
{
  vtkNew<vtkXMLImageDataReader> reader;
  std::string error;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&error);
  onError->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void* callData)
    {
      auto* text = static_cast<std::string*>(clientData);
      if (text->empty() && callData)
      {
        *text = static_cast<const char*>(callData);
      }
    });
  reader->AddObserver(vtkCommand::ErrorEvent, onError);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, onError);
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  if (!error.empty() || !image || image->GetNumberOfPoints() == 0)
  {
    const std::string reason = error.empty() ? "no image data" : io_detail::CleanMessage(error);
    throw VolumeReadError(path + ": cannot read VTK image: " + reason);
  }
  if (!image->GetPointData()->GetScalars() ||
    image->GetPointData()->GetScalars()->GetNumberOfComponents() != 1)
  {
    throw VolumeReadError(path + ": VTK image has no single-component point scalars");
  }
  return VtkImageToVolume(image);
}

Volume ReadDicomFolder(const std::string& folder,
  const VolumeReadOptions& options,
  const ProgressReporter& progress)
{
  const std::vector<DicomSeriesInfo> series = ListDicomSeries(folder);
  if (series.empty())
  {
    throw VolumeReadError(folder + ": no DICOM series found in this folder");
  }
  std::string uid = options.dicomSeriesUid;
  if (uid.empty())
  {
    if (series.size() > 1)
    {
      std::string msg =
        folder + ": " + std::to_string(series.size()) + " DICOM series, choose one by UID:";
      for (const DicomSeriesInfo& s : series)
      {
        msg +=
          " [" + s.uid + " \"" + s.description + "\" " + std::to_string(s.sliceCount) + " slices]";
      }
      throw VolumeReadError(msg);
    }
    uid = series.front().uid;
  }
  else if (std::none_of(
             series.begin(), series.end(), [&](const DicomSeriesInfo& s) { return s.uid == uid; }))
  {
    throw VolumeReadError(folder + ": no DICOM series with UID " + uid);
  }
  auto names = itk::GDCMSeriesFileNames::New();
  names->SetUseSeriesDetails(false);
  names->SetDirectory(folder);
  // GDCM's series helper orders the files by position along the slice normal.
  const std::vector<std::string> files = names->GetFileNames(uid);
  using ReaderType = itk::ImageSeriesReader<FloatImage>;
  auto reader = ReaderType::New();
  reader->SetImageIO(itk::GDCMImageIO::New());
  reader->SetFileNames(files);
  detail::WatchFilter(reader, progress, "read");
  reader->Update();
  return FromItk(reader->GetOutput());
}

template<typename TImage>
void WriteItk(const TImage* image, const std::string& path, const std::string& reportedPath)
{
  const VolumeFormat format = FormatOf(path);
  if (format == VolumeFormat::Unknown || format == VolumeFormat::Vti)
  {
    throw VolumeWriteError(
      reportedPath + ": unknown volume extension (use .nrrd .nhdr .nii .nii.gz .mha .mhd .vti)");
  }
  try
  {
    auto writer = itk::ImageFileWriter<TImage>::New();
    writer->SetFileName(path);
    writer->SetImageIO(MakeImageIO(format));
    writer->SetInput(image);
    writer->UseCompressionOn();
    writer->Update();
  }
  catch (const itk::ExceptionObject& e)
  {
    throw VolumeWriteError(reportedPath + ": " + OneLine(e));
  }
}

void WriteVti(vtkImageData* image, const std::string& path, const std::string& reportedPath)
{
  vtkNew<vtkXMLImageDataWriter> writer;
  // Errors are reported through the exception below, not printed by VTK.
  vtkNew<vtkCallbackCommand> quiet;
  quiet->SetCallback([](vtkObject*, unsigned long, void*, void*) {});
  writer->AddObserver(vtkCommand::ErrorEvent, quiet);
  writer->AddObserver(vtkCommand::WarningEvent, quiet);
  writer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, quiet);
  writer->SetFileName(path.c_str());
  writer->SetInputData(image);
  writer->SetDataModeToAppended();
  writer->SetCompressorTypeToZLib();
  if (writer->Write() != 1 || writer->GetErrorCode() != 0)
  {
    throw VolumeWriteError(reportedPath + ": cannot write VTK image (" +
      (writer->GetErrorCode() == vtkErrorCode::OutOfDiskSpaceError ? std::string("disk full")
                                                                   : std::string("write error")) +
      ")");
  }
}

/// All-or-nothing volume writes. The writer writes into a fresh hidden folder beside the
/// target under the target's own name (so that a .mhd or .nhdr header names its data file by
/// the final name); the result is read back through the same validator as the readers use
/// (ITK's NIfTI and MetaImage writers report success for a file cut short by a full disk), then
/// the files are published by AtomicWriteAll (flushed, the data files before the header, all or
/// none). Any failure removes the folder and everything in it; the previous target, if any, is
/// untouched.
void WriteAtomically(const std::string& path, const std::function<void(const std::string&)>& write)
{
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
  {
    throw VolumeWriteError(path + ": the folder " + folder.string() + " does not exist");
  }
  if (fs::is_directory(target, ec))
  {
    throw VolumeWriteError(path + ": is a folder");
  }
  fs::path staging;
  for (int attempt = 0; attempt < 100 && staging.empty(); ++attempt)
  {
    const fs::path candidate = folder /
      ("." + target.filename().string() + ".bender-tmp-" + std::to_string(::getpid()) + "-" +
        std::to_string(std::random_device{}() % 1000000));
    if (fs::create_directory(candidate, ec) && !ec)
    {
      staging = candidate;
    }
  }
  if (staging.empty())
  {
    throw VolumeWriteError(
      path + ": cannot create a temporary folder beside it (" + ec.message() + ")");
  }
  const std::string staged = (staging / target.filename()).string();
  try
  {
    write(staged);
    std::string problem;
    if (!io_detail::CheckVolumeFile(staged, io_detail::MaxVolumeBytes * 2, problem))
    {
      throw VolumeWriteError(
        path + ": the written file is incomplete, disk full? (" + problem + ")");
    }
    // Data files first, the header (the target itself) last; each one's content is the staged
    // file, moved to the temporary name AtomicWriteAll gives it.
    std::vector<AtomicFile> files;
    for (const auto& entry : fs::directory_iterator(staging))
    {
      const fs::path file = entry.path();
      files.push_back({ (folder / file.filename()).string(),
        [file](const std::string& temp, std::string& why)
        {
          std::error_code moved;
          fs::rename(file, temp, moved);
          why = moved ? "cannot move the written file (" + moved.message() + ")" : "";
          return !moved;
        } });
    }
    std::stable_partition(files.begin(),
      files.end(),
      [&](const AtomicFile& f) { return fs::path(f.path).filename() != target.filename(); });
    if (!AtomicWriteAll(files, problem))
    {
      throw VolumeWriteError(path + ": " + problem);
    }
  }
  catch (...)
  {
    fs::remove_all(staging, ec);
    throw;
  }
  fs::remove_all(staging, ec);
}

} // namespace

std::vector<DicomSeriesInfo> ListDicomSeries(const std::string& folder)
{
  RegisterImageIOFactories();
  if (!std::filesystem::is_directory(folder))
  {
    throw VolumeReadError(folder + ": not a folder");
  }
  std::vector<DicomSeriesInfo> result;
  try
  {
    auto names = itk::GDCMSeriesFileNames::New();
    names->SetUseSeriesDetails(false);
    names->SetDirectory(folder);
    for (const std::string& uid : names->GetSeriesUIDs())
    {
      DicomSeriesInfo info;
      info.uid = uid;
      const std::vector<std::string> files = names->GetFileNames(uid);
      info.sliceCount = files.size();
      if (!files.empty())
      {
        auto io = itk::GDCMImageIO::New();
        io->SetFileName(files.front());
        io->ReadImageInformation();
        std::string description;
        if (io->GetValueFromTag("0008|103e", description))
        {
          while (
            !description.empty() && std::isspace(static_cast<unsigned char>(description.back())))
          {
            description.pop_back();
          }
          info.description = description;
        }
      }
      result.push_back(info);
    }
  }
  catch (const itk::ExceptionObject& e)
  {
    throw VolumeReadError(folder + ": " + OneLine(e));
  }
  std::sort(result.begin(),
    result.end(),
    [](const DicomSeriesInfo& a, const DicomSeriesInfo& b) { return a.uid < b.uid; });
  return result;
}

Volume ReadVolume(const std::string& path,
  const VolumeReadOptions& options,
  const ProgressReporter& progress)
{
  RegisterImageIOFactories();
  if (!std::filesystem::exists(path))
  {
    throw VolumeReadError(path + ": no such file or folder");
  }
  Volume volume;
  try
  {
    if (std::filesystem::is_directory(path))
    {
      volume = ReadDicomFolder(path, options, progress);
    }
    else
    {
      const VolumeFormat format = FormatOf(path);
      if (format == VolumeFormat::Unknown)
      {
        throw VolumeReadError(path +
          ": unknown volume extension (use .nrrd .nhdr .nii .nii.gz .mha .mhd .vti or a DICOM "
          "folder)");
      }
      // Before ITK or VTK sees it: a regular file whose header parses safely and whose data is
      // all there (ITK fills a truncated volume with zeros; long NRRD or MetaImage header
      // fields overflow its buffers; a FIFO or /dev/zero would block or never end).
      std::string problem;
      if (!io_detail::CheckVolumeFile(path, io_detail::MaxVolumeBytes, problem))
      {
        throw VolumeReadError(path + ": " + problem);
      }
      volume = format == VolumeFormat::Vti ? ReadVti(path) : ReadItkFile(path, format, progress);
    }
  }
  catch (const itk::ProcessAborted&)
  {
    throw SegmentationCancelled(path + ": reading cancelled");
  }
  catch (const itk::ExceptionObject& e)
  {
    throw VolumeReadError(path + ": " + OneLine(e));
  }
  CheckGeometry(volume.geometry, path);
  if (volume.voxels.size() != volume.geometry.VoxelCount())
  {
    throw VolumeReadError(path + ": voxel count does not match the header");
  }
  return volume;
}

void WriteVolume(const Volume& volume, const std::string& path)
{
  if (volume.geometry.VoxelCount() == 0 || volume.voxels.size() != volume.geometry.VoxelCount())
  {
    throw VolumeWriteError(path + ": empty or inconsistent volume");
  }
  if (FormatOf(path) == VolumeFormat::Unknown)
  {
    throw VolumeWriteError(
      path + ": unknown volume extension (use .nrrd .nhdr .nii .nii.gz .mha .mhd .vti)");
  }
  if (FormatOf(path) == VolumeFormat::Vti)
  {
    vtkSmartPointer<vtkImageData> image = VolumeToVtkImage(volume);
    WriteAtomically(path, [&](const std::string& staged) { WriteVti(image, staged, path); });
    return;
  }
  auto image = detail::WrapVolume(volume);
  WriteAtomically(
    path, [&](const std::string& staged) { WriteItk<FloatImage>(image, staged, path); });
}

void WriteLabelMap(const LabelMap& mask, const std::string& path)
{
  if (mask.geometry.VoxelCount() == 0 || mask.voxels.size() != mask.geometry.VoxelCount())
  {
    throw VolumeWriteError(path + ": empty or inconsistent mask");
  }
  if (FormatOf(path) == VolumeFormat::Unknown)
  {
    throw VolumeWriteError(
      path + ": unknown volume extension (use .nrrd .nhdr .nii .nii.gz .mha .mhd .vti)");
  }
  if (FormatOf(path) == VolumeFormat::Vti)
  {
    vtkSmartPointer<vtkImageData> image = LabelMapToVtkImage(mask);
    WriteAtomically(path, [&](const std::string& staged) { WriteVti(image, staged, path); });
    return;
  }
  auto image = detail::WrapLabelMap(mask);
  WriteAtomically(
    path, [&](const std::string& staged) { WriteItk<MaskImage>(image, staged, path); });
}

} // namespace bender
