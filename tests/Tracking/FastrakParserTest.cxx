// The stream decoder on byte-stream fixtures built from the protocol.
#include "FastrakParser.h"
#include "TrackingTestUtilities.h"

#include <cstring>
#include <limits>

namespace bender::test
{
namespace
{

std::vector<TrackerPose> Decode(FastrakParser& parser, const Bytes& bytes)
{
  return parser.Feed(bytes, 0.0);
}

FastrakParser AsciiParser()
{
  FastrakParser::Options o;
  o.format = FastrakFormat::Ascii;
  return FastrakParser(o);
}

void SetFloat(Bytes& bytes, std::size_t at, float value)
{
  std::uint32_t bits;
  std::memcpy(&bits, &value, 4);
  for (int b = 0; b < 4; ++b)
  {
    bytes[at + std::size_t(b)] = std::uint8_t(bits >> (8 * b));
  }
}

TEST(FastrakParser, BinaryRecordLayoutIsThe34BytesOfTheOutputList)
{
  const TrackerPose pose = MakePose(3, { 10.0, -20.0, 30.0 }, { 1, 0, 0, 0 }, true, 'X');
  const Bytes r = EncodeFastrakRecord(pose, FastrakFormat::Binary);
  ASSERT_EQ(r.size(), 34u);
  EXPECT_EQ(r[0], '0');
  EXPECT_EQ(r[1], '3');
  EXPECT_EQ(r[2], 'X');
  // x = 1.0 cm as little-endian float32: 00 00 80 3f
  EXPECT_EQ(r[3], 0x00);
  EXPECT_EQ(r[5], 0x80);
  EXPECT_EQ(r[6], 0x3f);
  EXPECT_EQ(r[31], ' ');
  EXPECT_EQ(r[32], '1');
  EXPECT_EQ(r[33], ' ');
}

TEST(FastrakParser, BinaryCleanStreamDecodesExactly)
{
  FastrakParser parser;
  const std::vector<TrackerPose> poses = SamplePoses();
  const std::vector<TrackerPose> got = Decode(parser, Encode(poses, FastrakFormat::Binary));
  ASSERT_EQ(got.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    ExpectPoseEq(ExpectedBinary(poses[i]), got[i]);
  }
  EXPECT_EQ(parser.Statistics().records, poses.size());
  EXPECT_EQ(parser.Statistics().garbageBytes, 0u);
  EXPECT_EQ(parser.Statistics().malformed, 0u);
  EXPECT_EQ(parser.Buffered(), 0u);
}

TEST(FastrakParser, BinaryDecodesWhenSplitAtEveryByteOffset)
{
  const std::vector<TrackerPose> poses = SamplePoses();
  const Bytes stream = Encode(poses, FastrakFormat::Binary);
  for (std::size_t cut = 0; cut <= stream.size(); ++cut)
  {
    FastrakParser parser;
    std::vector<TrackerPose> got;
    parser.Feed(stream.data(), cut, 1.0, got);
    parser.Feed(stream.data() + cut, stream.size() - cut, 2.0, got);
    ASSERT_EQ(got.size(), poses.size()) << "cut at " << cut;
    for (std::size_t i = 0; i < poses.size(); ++i)
    {
      ExpectPoseEq(ExpectedBinary(poses[i]), got[i]);
      // A record is stamped with the time of the chunk that completed it.
      EXPECT_EQ(got[i].time, (i + 1) * 34 <= cut ? 1.0 : 2.0);
    }
  }
  // One byte at a time.
  FastrakParser parser;
  std::vector<TrackerPose> got;
  for (std::uint8_t b : stream)
  {
    parser.Feed(&b, 1, 0.0, got);
  }
  EXPECT_EQ(got.size(), poses.size());
}

TEST(FastrakParser, BinaryResynchronisesAfterLeadingGarbage)
{
  // Garbage that contains '0', "01" and the start of a record.
  Bytes stream = { 'x', '0', '0', '1', 0xff, '0', '2', ' ', 0x00, 0x12, '\r', '\n' };
  const Bytes garbageSize(stream.begin(), stream.end());
  const std::vector<TrackerPose> poses = SamplePoses();
  const Bytes records = Encode(poses, FastrakFormat::Binary);
  stream.insert(stream.end(), records.begin(), records.end());
  FastrakParser parser;
  const std::vector<TrackerPose> got = Decode(parser, stream);
  ASSERT_EQ(got.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    ExpectPoseEq(ExpectedBinary(poses[i]), got[i]);
  }
  EXPECT_GT(parser.Statistics().garbageBytes + parser.Statistics().malformed, 0u);
  EXPECT_EQ(parser.Statistics().dropped, 0u);
}

TEST(FastrakParser, BinaryLostByteLosesOnlyThatRecord)
{
  const std::vector<TrackerPose> poses = SamplePoses();
  for (std::size_t lost = 0; lost < 34; ++lost)
  {
    Bytes stream = Encode(poses, FastrakFormat::Binary);
    stream.erase(stream.begin() + std::ptrdiff_t(34 + lost)); // a byte of the second record
    FastrakParser parser;
    const std::vector<TrackerPose> got = Decode(parser, stream);
    ASSERT_EQ(got.size(), 3u) << "lost byte " << lost;
    ExpectPoseEq(ExpectedBinary(poses[0]), got[0]);
    ExpectPoseEq(ExpectedBinary(poses[2]), got[1]);
    ExpectPoseEq(ExpectedBinary(poses[3]), got[2]);
  }
}

TEST(FastrakParser, BinaryTruncatedRecordAtEndIsCounted)
{
  const std::vector<TrackerPose> poses = SamplePoses();
  Bytes stream = Encode(poses, FastrakFormat::Binary);
  stream.resize(stream.size() - 10);
  FastrakParser parser;
  const std::vector<TrackerPose> got = Decode(parser, stream);
  EXPECT_EQ(got.size(), 3u);
  EXPECT_EQ(parser.Buffered(), 24u);
  parser.Finish();
  EXPECT_EQ(parser.Statistics().truncated, 1u);
  EXPECT_EQ(parser.Buffered(), 0u);
}

TEST(FastrakParser, BinaryCorruptStatusIsMalformedAndSkipped)
{
  const std::vector<TrackerPose> poses = SamplePoses();
  Bytes stream = Encode(poses, FastrakFormat::Binary);
  stream[34 + 2] = 0x07; // status byte of the second record
  FastrakParser parser;
  const std::vector<TrackerPose> got = Decode(parser, stream);
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[1].station, poses[2].station);
  EXPECT_GE(parser.Statistics().malformed, 1u);
}

TEST(FastrakParser, BinaryWarningStatusIsPassedOnAndCounted)
{
  TrackerPose pose = SamplePoses()[0];
  pose.status = 'W';
  FastrakParser parser;
  const std::vector<TrackerPose> got =
    Decode(parser, EncodeFastrakRecord(pose, FastrakFormat::Binary));
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].status, 'W');
  EXPECT_EQ(parser.Statistics().warnings, 1u);
}

TEST(FastrakParser, BinaryNaNIsDroppedAndCounted)
{
  const std::vector<TrackerPose> poses = SamplePoses();
  for (std::size_t field = 0; field < 7; ++field)
  {
    Bytes stream = Encode(poses, FastrakFormat::Binary);
    SetFloat(stream, 34 + 3 + 4 * field, std::numeric_limits<float>::quiet_NaN());
    FastrakParser parser;
    const std::vector<TrackerPose> got = Decode(parser, stream);
    ASSERT_EQ(got.size(), 3u) << "NaN in field " << field;
    for (const TrackerPose& p : got)
    {
      EXPECT_TRUE(IsFinite(p.position));
    }
    EXPECT_EQ(parser.Statistics().dropped, 1u);
    EXPECT_EQ(parser.Statistics().records, 3u);
  }
  Bytes inf = Encode(poses, FastrakFormat::Binary);
  SetFloat(inf, 3, std::numeric_limits<float>::infinity());
  FastrakParser parser;
  EXPECT_EQ(Decode(parser, inf).size(), 3u);
  EXPECT_EQ(parser.Statistics().dropped, 1u);
}

TEST(FastrakParser, BinaryWrongStationIsDroppedAndCounted)
{
  const std::vector<TrackerPose> poses = SamplePoses();
  for (std::uint8_t station : { '0', '5', '9' })
  {
    Bytes stream = Encode(poses, FastrakFormat::Binary);
    stream[1] = station;
    FastrakParser parser;
    const std::vector<TrackerPose> got = Decode(parser, stream);
    ASSERT_EQ(got.size(), 3u);
    ExpectPoseEq(ExpectedBinary(poses[1]), got[0]);
    EXPECT_EQ(parser.Statistics().dropped, 1u);
  }
}

TEST(FastrakParser, BinaryBadQuaternionAndOutOfRangePositionAreDropped)
{
  std::vector<TrackerPose> poses = SamplePoses();
  poses[1].orientation = { 0.5, 0.0, 0.0, 0.0 }; // |q| = 0.5
  poses[2].position = { 0.0, 2.0e5, 0.0 };       // 200 m
  FastrakParser parser;
  const std::vector<TrackerPose> got = Decode(parser, Encode(poses, FastrakFormat::Binary));
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(parser.Statistics().dropped, 2u);
}

TEST(FastrakParser, QuaternionsAreNormalised)
{
  TrackerPose pose = SamplePoses()[0];
  pose.orientation = { 1.02, 0.0, 0.0, 0.0 };
  FastrakParser parser;
  const std::vector<TrackerPose> got =
    Decode(parser, EncodeFastrakRecord(pose, FastrakFormat::Binary));
  ASSERT_EQ(got.size(), 1u);
  EXPECT_DOUBLE_EQ(got[0].orientation.w, 1.0);
}

TEST(FastrakParser, InchesAreConvertedToMillimetres)
{
  FastrakParser::Options o;
  o.units = FastrakUnits::Inches;
  FastrakParser parser(o);
  const TrackerPose pose = MakePose(1, { 10.0, 0.0, 0.0 }, { 1, 0, 0, 0 }, false); // 1 unit
  const std::vector<TrackerPose> got =
    Decode(parser, EncodeFastrakRecord(pose, FastrakFormat::Binary));
  ASSERT_EQ(got.size(), 1u);
  EXPECT_DOUBLE_EQ(got[0].position.x, 25.4);
}

TEST(FastrakParser, AsciiFixedColumnsRunTogether)
{
  // x = 30.01 cm and y = -150.70 cm run together, as the Fastrak prints them.
  const std::string record = "01 "
                             "  30.01"
                             "-150.70"
                             "   2.50"
                             " 0.7071"
                             " 0.0000"
                             "-0.7071"
                             " 0.0000"
                             " 1 ";
  ASSERT_EQ(record.size(), FastrakParser::AsciiRecordSize);
  FastrakParser parser = AsciiParser();
  const std::vector<TrackerPose> got = Decode(parser, Bytes(record.begin(), record.end()));
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].station, 1);
  EXPECT_NEAR(got[0].position.x, 300.1, 1e-9);
  EXPECT_NEAR(got[0].position.y, -1507.0, 1e-9);
  EXPECT_NEAR(got[0].position.z, 25.0, 1e-9);
  EXPECT_NEAR(got[0].orientation.w, std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(got[0].orientation.y, -std::sqrt(0.5), 1e-9);
  EXPECT_TRUE(got[0].button);
}

TEST(FastrakParser, AsciiStreamSplitAtEveryOffsetWithCrLfAndGarbage)
{
  const std::vector<TrackerPose> poses = SamplePoses();
  Bytes stream = { 'g', '0', 'x' };
  for (const TrackerPose& p : poses)
  {
    const Bytes r = EncodeFastrakRecord(p, FastrakFormat::Ascii);
    ASSERT_EQ(r.size(), 55u);
    stream.insert(stream.end(), r.begin(), r.end());
    stream.push_back('\r');
    stream.push_back('\n');
  }
  for (std::size_t cut = 0; cut <= stream.size(); ++cut)
  {
    FastrakParser parser = AsciiParser();
    std::vector<TrackerPose> got;
    parser.Feed(stream.data(), cut, 0.0, got);
    parser.Feed(stream.data() + cut, stream.size() - cut, 0.0, got);
    ASSERT_EQ(got.size(), poses.size()) << "cut at " << cut;
    for (std::size_t i = 0; i < poses.size(); ++i)
    {
      // ASCII has 2 decimals of cm and 4 of the quaternion.
      TrackerPose expected = poses[i];
      EXPECT_EQ(got[i].station, expected.station);
      EXPECT_EQ(got[i].button, expected.button);
      EXPECT_NEAR(got[i].position.x, expected.position.x, 0.0501);
      EXPECT_NEAR(got[i].position.y, expected.position.y, 0.0501);
      EXPECT_NEAR(got[i].position.z, expected.position.z, 0.0501);
      EXPECT_NEAR(std::fabs(Dot4(got[i].orientation, expected.orientation)), 1.0, 1e-6);
    }
    EXPECT_EQ(parser.Statistics().garbageBytes + parser.Statistics().malformed, 3u);
  }
}

TEST(FastrakParser, AsciiCorruptFieldsAreNotPassedOn)
{
  const std::vector<TrackerPose> poses = SamplePoses();
  const Bytes clean = Encode(poses, FastrakFormat::Ascii);
  const std::vector<std::string> bad = { "   nan ", " 12a.00", "  1.2.3", "       ", "-  1.00" };
  for (const std::string& field : bad)
  {
    Bytes stream = clean;
    std::copy(field.begin(), field.end(), stream.begin() + 55 + 3 + 7); // y of record 2
    FastrakParser parser = AsciiParser();
    const std::vector<TrackerPose> got = Decode(parser, stream);
    ASSERT_EQ(got.size(), 3u) << "field '" << field << "'";
    EXPECT_EQ(got[1].station, poses[2].station);
    EXPECT_GE(parser.Statistics().malformed + parser.Statistics().dropped, 1u);
  }
  Bytes wrongStation = clean;
  wrongStation[1] = '7';
  FastrakParser parser = AsciiParser();
  EXPECT_EQ(Decode(parser, wrongStation).size(), 3u);
  EXPECT_EQ(parser.Statistics().dropped, 1u);
}

TEST(FastrakParser, ResetForgetsBufferAndCounters)
{
  FastrakParser parser;
  const Bytes stream = Encode(SamplePoses(), FastrakFormat::Binary);
  parser.Feed(Bytes(stream.begin(), stream.begin() + 50));
  EXPECT_GT(parser.Buffered(), 0u);
  parser.Reset();
  EXPECT_EQ(parser.Buffered(), 0u);
  EXPECT_EQ(parser.Statistics().records, 0u);
}

TEST(FastrakParser, EncoderRejectsBadStationAndOverwideAsciiField)
{
  TrackerPose pose = SamplePoses()[0];
  pose.station = 5;
  EXPECT_THROW(EncodeFastrakRecord(pose, FastrakFormat::Binary), TrackingConfigurationError);
  pose.station = 1;
  pose.position = { 1.0e5, 0, 0 };
  EXPECT_THROW(EncodeFastrakRecord(pose, FastrakFormat::Ascii), TrackingConfigurationError);
}

} // namespace
} // namespace bender::test
