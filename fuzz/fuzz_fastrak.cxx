// libFuzzer harness for the Fastrak byte parser: the first byte picks the format and the
// chunking, the rest is the stream. Every pose passed on must be finite and normalised.

#include "FastrakParser.h"
#include "FuzzSupport.h"

#include <cmath>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0)
  {
    return 0;
  }
  bender::FastrakParser::Options options;
  options.format = (data[0] & 1) ? bender::FastrakFormat::Ascii : bender::FastrakFormat::Binary;
  options.units = (data[0] & 2) ? bender::FastrakUnits::Inches : bender::FastrakUnits::Centimetres;
  const std::size_t chunk = 1 + (data[0] >> 2);
  bender::FastrakParser parser(options);
  std::vector<bender::TrackerPose> poses;
  for (std::size_t at = 1; at < size; at += chunk)
  {
    const std::size_t n = std::min(chunk, size - at);
    parser.Feed(data + at, n, static_cast<double>(at), poses);
  }
  parser.Finish();
  for (const bender::TrackerPose& pose : poses)
  {
    const double values[] = { pose.position.x,
      pose.position.y,
      pose.position.z,
      pose.orientation.w,
      pose.orientation.x,
      pose.orientation.y,
      pose.orientation.z };
    for (const double v : values)
    {
      if (!std::isfinite(v))
      {
        std::abort();
      }
    }
  }
  return 0;
}
