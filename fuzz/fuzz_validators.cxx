// libFuzzer harness for the byte-level pre-validators that have no reader behind them in
// this build (the volume headers are read by ITK, which the fuzz build leaves out), and for
// the structural mesh validators on their own. BENDER_FUZZ_VALIDATOR picks one:
//   1 NRRD (.nrrd), 2 NRRD detached header (.nhdr), 3 MetaImage (.mha), 4 MetaImage (.mhd),
//   5 NIfTI (.nii), 6 NIfTI gzip (.nii.gz), 7 VTK XML image (.vti),
//   8 legacy VTK, 9 VTK XML PolyData, 10 PLY structure.
// A validator must answer for any input without crashing, allocating beyond the budget or
// reading out of bounds, and its problem must be one clean line.

#include "FuzzSupport.h"
#include "InputValidation.h"
#include "PlyValidation.h"
#include "VolumeValidation.h"

#include <string>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  using namespace bender::io_detail;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  std::string problem;
  bool ok = false;
  const std::uint64_t budget = std::uint64_t(64) << 20; // keep each run small
  switch (BENDER_FUZZ_VALIDATOR)
  {
    case 1:
      ok = CheckVolumeBytes(".nrrd", bytes, "", budget, problem);
      break;
    case 2:
      ok = CheckVolumeBytes(".nhdr", bytes, "", budget, problem);
      break;
    case 3:
      ok = CheckVolumeBytes(".mha", bytes, "", budget, problem);
      break;
    case 4:
      ok = CheckVolumeBytes(".mhd", bytes, "", budget, problem);
      break;
    case 5:
      ok = CheckVolumeBytes(".nii", bytes, "", budget, problem);
      break;
    case 6:
      ok = CheckVolumeBytes(".nii.gz", bytes, "", budget, problem);
      break;
    case 7:
      ok = CheckVolumeBytes(".vti", bytes, "", budget, problem);
      break;
    case 8:
      ok = CheckLegacyVtk(bytes, problem);
      break;
    case 9:
      ok = CheckVtkXml(bytes, "PolyData", budget, problem);
      break;
    case 10:
      ok = CheckPlyBytes(bytes, problem);
      break;
    default:
      std::abort();
  }
  if (!ok)
  {
    bender_fuzz::CheckMessage(problem);
  }
  return 0;
}
