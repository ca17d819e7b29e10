#include "VolumeIO.h"

#include "ItkVtkBridge.h"
#include "Private/ItkImage.h"

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
#include <vtkExecutive.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLImageDataWriter.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <sstream>

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

std::string Lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool EndsWith(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

VolumeFormat FormatOf(const std::string& path)
{
  const std::string p = Lower(path);
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

/// ITK messages span several lines and start with the source location: keep the description.
std::string OneLine(const itk::ExceptionObject& e)
{
  std::string text = e.GetDescription();
  std::replace(text.begin(), text.end(), '\n', ' ');
  // Drop ITK's "itk::ERROR: NrrdImageIO(0x55...): " prefix.
  if (text.rfind("itk::ERROR: ", 0) == 0 && text.find("): ") != std::string::npos)
  {
    text = text.substr(text.find("): ") + 3);
  }
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
  {
    text.pop_back();
  }
  return text;
}

/// The readers also work through ITK's factories (e.g. GDCM inside ImageSeriesReader): register
/// them explicitly so that a static library linked into any executable finds them.
void RegisterImageIOFactories()
{
  static std::once_flag once;
  std::call_once(once, [] {
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
  onError->SetCallback([](vtkObject*, unsigned long, void* clientData, void* callData) {
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
    std::string reason = error.empty() ? "no image data" : error;
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    throw VolumeReadError(path + ": cannot read VTK image: " + reason);
  }
  if (!image->GetPointData()->GetScalars() ||
    image->GetPointData()->GetScalars()->GetNumberOfComponents() != 1)
  {
    throw VolumeReadError(path + ": VTK image has no single-component point scalars");
  }
  return VtkImageToVolume(image);
}

Volume ReadDicomFolder(
  const std::string& folder, const VolumeReadOptions& options, const ProgressReporter& progress)
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
      std::string msg = folder + ": " + std::to_string(series.size()) +
        " DICOM series, choose one by UID:";
      for (const DicomSeriesInfo& s : series)
      {
        msg += " [" + s.uid + " \"" + s.description + "\" " + std::to_string(s.sliceCount) +
          " slices]";
      }
      throw VolumeReadError(msg);
    }
    uid = series.front().uid;
  }
  else if (std::none_of(series.begin(), series.end(),
             [&](const DicomSeriesInfo& s) { return s.uid == uid; }))
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

template <typename TImage>
void WriteItk(const TImage* image, const std::string& path)
{
  const VolumeFormat format = FormatOf(path);
  if (format == VolumeFormat::Unknown || format == VolumeFormat::Vti)
  {
    throw VolumeWriteError(path + ": unknown volume extension (use .nrrd .nhdr .nii .nii.gz .mha .mhd .vti)");
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
    throw VolumeWriteError(path + ": " + OneLine(e));
  }
}

void WriteVti(vtkImageData* image, const std::string& path)
{
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(image);
  writer->SetDataModeToAppended();
  writer->SetCompressorTypeToZLib();
  if (writer->Write() != 1)
  {
    throw VolumeWriteError(path + ": cannot write VTK image");
  }
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
          while (!description.empty() && std::isspace(static_cast<unsigned char>(description.back())))
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
  std::sort(result.begin(), result.end(),
    [](const DicomSeriesInfo& a, const DicomSeriesInfo& b) { return a.uid < b.uid; });
  return result;
}

Volume ReadVolume(
  const std::string& path, const VolumeReadOptions& options, const ProgressReporter& progress)
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
        throw VolumeReadError(
          path + ": unknown volume extension (use .nrrd .nhdr .nii .nii.gz .mha .mhd .vti or a DICOM folder)");
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
  if (FormatOf(path) == VolumeFormat::Vti)
  {
    WriteVti(VolumeToVtkImage(volume), path);
    return;
  }
  auto image = detail::WrapVolume(volume);
  WriteItk<FloatImage>(image, path);
}

void WriteLabelMap(const LabelMap& mask, const std::string& path)
{
  if (mask.geometry.VoxelCount() == 0 || mask.voxels.size() != mask.geometry.VoxelCount())
  {
    throw VolumeWriteError(path + ": empty or inconsistent mask");
  }
  if (FormatOf(path) == VolumeFormat::Vti)
  {
    WriteVti(LabelMapToVtkImage(mask), path);
    return;
  }
  auto image = detail::WrapLabelMap(mask);
  WriteItk<MaskImage>(image, path);
}

} // namespace bender
