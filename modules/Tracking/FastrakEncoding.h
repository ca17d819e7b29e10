#ifndef bender_FastrakEncoding_h
#define bender_FastrakEncoding_h

#include "FastrakParser.h"
#include "TrackerPose.h"

#include <cstdint>
#include <vector>

namespace bender
{

/// The bytes a Fastrak sends for `pose` with the output list `O n,2,11,16,0` in metric units
/// (the inverse of FastrakParser): binary (34 bytes, position as float32 centimetres) or
/// ASCII (55 characters, "%7.2f" centimetres and "%7.4f" quaternion components). Used by the
/// simulator's recordings and by the tests' byte-stream fixtures.
/// Throws TrackingConfigurationError for a station outside 1..4.
std::vector<std::uint8_t> EncodeFastrakRecord(const TrackerPose& pose, FastrakFormat format);

} // namespace bender

#endif
