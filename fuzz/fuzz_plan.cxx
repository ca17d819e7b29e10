// libFuzzer harness for the warp-plan parser: any text gives a plan or a WarpPlanError.

#include "FuzzSupport.h"
#include "WarpPlanIO.h"

#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  try
  {
    bender::ParseWarpPlan(text, "fuzz.bender.json");
  }
  catch (const bender::WarpPlanError& e)
  {
    bender_fuzz::CheckMessage(e.what());
  }
  return 0;
}
