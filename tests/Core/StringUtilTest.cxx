#include "StringUtil.h"

#include <gtest/gtest.h>

namespace
{

TEST(StringUtil, ToLowerFoldsAsciiOnly)
{
  EXPECT_EQ(bender::ToLower("Aneurysm.STL"), "aneurysm.stl");
  EXPECT_EQ(bender::ToLower("\xC3\x89"), "\xC3\x89"); // UTF-8 bytes are left as they are
  EXPECT_TRUE(bender::EqualsIgnoreCase("FASTRAK", "fastrak"));
  EXPECT_FALSE(bender::EqualsIgnoreCase("fastrak", "fastra"));
}

TEST(StringUtil, ExtensionsAndNames)
{
  EXPECT_EQ(bender::LowerExtension("/data/Vessel.STL"), ".stl");
  EXPECT_EQ(bender::LowerExtension("/data/noext"), "");
  EXPECT_EQ(bender::LowerExtension("/data.d/noext"), "");
  EXPECT_EQ(bender::LowerExtension("scan.nii.gz"), ".gz");
  EXPECT_EQ(bender::LowerDoubleExtension("scan.NII.GZ"), ".nii.gz");
  EXPECT_EQ(bender::LowerDoubleExtension("scan.nrrd"), ".nrrd");
  EXPECT_EQ(bender::DisplayName("/data/aneurysm.stl"), "aneurysm.stl");
  EXPECT_EQ(bender::DisplayName("aneurysm.stl"), "aneurysm.stl");
}

TEST(StringUtil, PointsInMessages)
{
  EXPECT_EQ(bender::FormatPoint({ { 1.0, -2.5, 0.0 } }), "(1, -2.5, 0)");
  EXPECT_EQ(bender::FormatPoint({ { 12.34567, 1e-3, 123.0 } }), "(12.35, 0.001, 123)");
  // Within a millionth of the largest coordinate: rounding noise, written 0.
  EXPECT_EQ(bender::FormatPoint({ { 12.34567, 1e-7, 123456.0 } }), "(12.35, 0, 1.235e+05)");
  EXPECT_EQ(bender::FormatPoint({ { 1.041e-17, -3.0, 2.0 } }), "(0, -3, 2)");
  EXPECT_EQ(bender::FormatPoint({ { 1e-9, 0.0, 0.0 } }), "(1e-09, 0, 0)");
}

TEST(StringUtil, CountsWithTheirNoun)
{
  EXPECT_EQ(bender::CountOf(1, "warp"), "1 warp");
  EXPECT_EQ(bender::CountOf(0, "warp"), "0 warps");
  EXPECT_EQ(bender::CountOf(2, "warp"), "2 warps");
}

TEST(StringUtil, AffixesAndTrim)
{
  EXPECT_TRUE(bender::StartsWith("solid wall", "solid"));
  EXPECT_FALSE(bender::StartsWith("so", "solid"));
  EXPECT_TRUE(bender::EndsWith("case.vtp", ".vtp"));
  EXPECT_FALSE(bender::EndsWith("vtp", ".vtp"));
  EXPECT_EQ(bender::Trim("  \tsolid wall\r\n"), "solid wall");
  EXPECT_EQ(bender::Trim(" \n "), "");
}

} // namespace
