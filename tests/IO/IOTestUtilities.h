#ifndef bender_IOTestUtilities_h
#define bender_IOTestUtilities_h

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <set>
#include <string>

#include <unistd.h>

namespace bender_test
{

/// A fresh folder under the system temporary folder, removed with its content at the end.
class TempDir
{
public:
  TempDir()
  {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "bender-io-";
    if (info)
    {
      name += std::string(info->test_suite_name()) + "-" + info->name() + "-";
    }
    name += std::to_string(::getpid()) + "-" + std::to_string(std::random_device{}());
    for (char& c : name)
    {
      if (c == '/')
      {
        c = '_';
      }
    }
    this->Path = std::filesystem::temp_directory_path() / name;
    std::filesystem::create_directories(this->Path);
  }
  ~TempDir()
  {
    std::error_code ec;
    std::filesystem::remove_all(this->Path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string operator/(const std::string& name) const { return (this->Path / name).string(); }
  const std::filesystem::path& path() const { return this->Path; }

  /// Names of the entries in the folder (to prove that no temporary file was left behind).
  std::set<std::string> Entries() const
  {
    std::set<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(this->Path))
    {
      names.insert(entry.path().filename().string());
    }
    return names;
  }

private:
  std::filesystem::path Path;
};

inline void WriteText(const std::string& path, const std::string& text)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

inline std::string ReadText(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// A file from tests/data.
inline std::string TestData(const std::string& relative)
{
  return std::string(BENDER_TEST_DATA_DIR) + "/" + relative;
}

/// A file fetched by scripts/fetch-data into data/external. Fails the calling test (with a
/// clear message, never a silent skip) when the file is missing.
#define BENDER_REQUIRE_EXTERNAL(var, name)                                                         \
  const std::string var = std::string(BENDER_EXTERNAL_DATA_DIR) + "/" + (name);                    \
  ASSERT_TRUE(std::filesystem::is_regular_file(var))                                               \
    << "missing real test data " << var << ": run scripts/fetch-data first"

} // namespace bender_test

#endif
