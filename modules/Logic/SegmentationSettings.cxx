// CheckSegmentationSettings: the parameter checks of the Segment panel and the session file,
// in a file of their own so that the session file reader can be built without ITK (fuzz/).

#include "SegmentationSession.h"

namespace bender
{

bool CheckSegmentationSettings(const SegmentationSettings& settings, std::string& problem)
{
  try
  {
    ValidateSegmentationParameters(settings.segmentation);
  }
  catch (const Error& e)
  {
    problem = e.what();
    return false;
  }
  if (!(settings.surface.smoothing >= 0.0 && settings.surface.smoothing <= 1.0))
  {
    problem = "smoothing: must be in [0, 1]";
    return false;
  }
  return true;
}

} // namespace bender
