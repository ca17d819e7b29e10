#ifndef bender_DicomTestSeries_h
#define bender_DicomTestSeries_h

// A DICOM series made for a test from one real slice (CT_small.dcm of data/external): the
// including test links ITK's GDCM IO (ITKIOGDCM) and has ITK's include folders.

#include <itkGDCMImageIO.h>
#include <itkImage.h>
#include <itkImageFileReader.h>
#include <itkImageFileWriter.h>
#include <itkMetaDataObject.h>

#include <string>
#include <vector>

namespace bender_test
{

/// Writes `count` slices as one series `seriesUid` ("description" in (0008,103E)) into
/// `folder`: slice k is the slice of `sourceDicom` at z = 2.5 k mm with its pixels offset by
/// 100 k, in files "<description>_<number>.dcm", number = fileOrder[k] (k when fileOrder is empty:
/// a shuffled order checks that readers sort by position, not by name).
inline void WriteDicomTestSeries(const std::string& folder,
  const std::string& sourceDicom,
  const std::string& seriesUid,
  const std::string& description,
  int count,
  const std::vector<int>& fileOrder = {})
{
  using Slice = itk::Image<short, 2>;
  auto reader = itk::ImageFileReader<Slice>::New();
  reader->SetImageIO(itk::GDCMImageIO::New());
  reader->SetFileName(sourceDicom);
  reader->Update();
  Slice::Pointer source = reader->GetOutput();
  for (int k = 0; k < count; ++k)
  {
    Slice::Pointer copy = Slice::New();
    copy->SetRegions(source->GetLargestPossibleRegion());
    copy->CopyInformation(source);
    copy->Allocate();
    const std::size_t n = source->GetLargestPossibleRegion().GetNumberOfPixels();
    for (std::size_t i = 0; i < n; ++i)
    {
      copy->GetBufferPointer()[i] = static_cast<short>(source->GetBufferPointer()[i] + 100 * k);
    }
    itk::MetaDataDictionary dict = reader->GetMetaDataDictionary();
    itk::EncapsulateMetaData<std::string>(dict, "0020|000e", seriesUid);
    itk::EncapsulateMetaData<std::string>(dict, "0008|103e", description);
    itk::EncapsulateMetaData<std::string>(
      dict, "0008|0018", seriesUid + "." + std::to_string(k + 1));
    itk::EncapsulateMetaData<std::string>(dict, "0020|0013", std::to_string(k + 1));
    itk::EncapsulateMetaData<std::string>(
      dict, "0020|0032", "-10\\-20\\" + std::to_string(2.5 * k));
    itk::EncapsulateMetaData<std::string>(dict, "0020|0037", "1\\0\\0\\0\\1\\0");
    itk::EncapsulateMetaData<std::string>(dict, "0028|1052", "0");
    itk::EncapsulateMetaData<std::string>(dict, "0028|1053", "1");
    copy->SetMetaDataDictionary(dict);
    auto io = itk::GDCMImageIO::New();
    io->KeepOriginalUIDOn();
    auto writer = itk::ImageFileWriter<Slice>::New();
    writer->SetImageIO(io);
    writer->SetInput(copy);
    const int number = fileOrder.empty() ? k : fileOrder.at(static_cast<std::size_t>(k));
    writer->SetFileName(folder + "/" + description + "_" + std::to_string(number) + ".dcm");
    writer->Update();
  }
}

} // namespace bender_test

#endif
