// bender::ContentHash, the one content hash (the flow cache's keys, the sweep's candidate
// hashes): MD5 as RFC 1321 defines it, the same digest however the bytes are split, a file
// hashed as its bytes, and its misuse refused.

#include "ContentHash.h"

#include "IOTestUtilities.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace
{

std::string HashOf(const std::string& bytes)
{
  bender::ContentHash hash;
  hash.Add(bytes);
  return hash.Finish();
}

} // namespace

TEST(ContentHash, IsMd5AsRfc1321Defines)
{
  // The test suite of RFC 1321, appendix A.5.
  EXPECT_EQ(HashOf(""), "d41d8cd98f00b204e9800998ecf8427e");
  EXPECT_EQ(HashOf("abc"), "900150983cd24fb0d6963f7d28e17f72");
  EXPECT_EQ(HashOf("message digest"), "f96b697d7cb7938d525a2f31aaf161d0");
}

TEST(ContentHash, DependsOnTheBytesOnlyNotOnHowTheyArePieced)
{
  // More than one 16 MiB piece of vtksysMD5_Append, with a zero byte inside.
  std::string bytes((1 << 24) + 1000, 'x');
  bytes[12345] = '\0';
  bytes[(1 << 24) + 7] = 'y';
  const std::string whole = HashOf(bytes);
  EXPECT_EQ(whole.size(), 32u);
  EXPECT_EQ(whole.find_first_not_of("0123456789abcdef"), std::string::npos) << whole;

  bender::ContentHash pieces;
  pieces.Add(bytes.data(), 3);
  pieces.Add(bytes.substr(3, 100000));
  pieces.Add(bytes.data() + 100003, bytes.size() - 100003);
  EXPECT_EQ(pieces.Finish(), whole);

  bytes[(1 << 24) + 7] = 'z';
  EXPECT_NE(HashOf(bytes), whole);
}

TEST(ContentHash, HashesAFileAsItsBytes)
{
  bender_test::TempDir dir;
  const std::string text = std::string("solid tube\n\0binary\n", 19);
  bender_test::WriteText(dir / "case.txt", text);
  bender::ContentHash file;
  ASSERT_TRUE(file.AddFile(dir / "case.txt"));
  EXPECT_EQ(file.Finish(), HashOf(text));

  bender::ContentHash missing;
  EXPECT_FALSE(missing.AddFile(dir / "no-such-file"));
  EXPECT_EQ(missing.Finish(), HashOf(""));
}

TEST(ContentHash, RefusesBytesAfterItsDigest)
{
  bender::ContentHash hash;
  hash.Add("abc");
  hash.Finish();
  EXPECT_THROW(hash.Add("more"), std::logic_error);
  EXPECT_THROW(hash.Finish(), std::logic_error);
}
