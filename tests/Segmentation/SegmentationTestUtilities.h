#ifndef bender_SegmentationTestUtilities_h
#define bender_SegmentationTestUtilities_h

#include "Volume.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
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
    std::string name = "bender-seg-";
    if (info)
    {
      name += std::string(info->test_suite_name()) + "-" + info->name() + "-";
    }
    name += std::to_string(::getpid()) + "-" + std::to_string(std::random_device{}());
    for (char& c : name)
    {
      c = (c == '/') ? '_' : c;
    }
    this->Path = std::filesystem::temp_directory_path() / name;
    std::filesystem::create_directories(this->Path);
  }
  ~TempDir()
  {
    std::error_code ignored;
    std::filesystem::remove_all(this->Path, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string File(const std::string& name) const { return (this->Path / name).string(); }
  std::filesystem::path Path;
};

/// Real data fetched by scripts/fetch-data. Missing data is a failure, never a skip.
inline std::string ExternalData(const std::string& name)
{
  const std::string path = std::string(BENDER_EXTERNAL_DATA_DIR) + "/" + name;
  if (!std::filesystem::exists(path))
  {
    ADD_FAILURE() << "missing test data " << path << ": run scripts/fetch-data";
  }
  return path;
}

/// An oblique, left-handed-free rotation (about the axis (1, 2, 2)/3 by 30 degrees).
inline std::array<double, 9> ObliqueDirection()
{
  const double a = M_PI / 6.0;
  const double u[3] = { 1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0 };
  const double c = std::cos(a), s = std::sin(a), t = 1.0 - c;
  return { { t * u[0] * u[0] + c,
    t * u[0] * u[1] - s * u[2],
    t * u[0] * u[2] + s * u[1],
    t * u[0] * u[1] + s * u[2],
    t * u[1] * u[1] + c,
    t * u[1] * u[2] - s * u[0],
    t * u[0] * u[2] - s * u[1],
    t * u[1] * u[2] + s * u[0],
    t * u[2] * u[2] + c } };
}

/// A volume of background `low` with bright balls (LPS mm centres and radii) of value `high`,
/// partial-volume smoothed over one voxel so that the iso-surface at the mid value is sub-voxel.
inline bender::Volume BallsVolume(const bender::ImageGeometry& g,
  const std::vector<std::pair<bender::Point3, double>>& balls,
  float low = 0.0f,
  float high = 100.0f)
{
  bender::Volume v;
  v.geometry = g;
  v.voxels.assign(g.VoxelCount(), low);
  const double h = std::min({ g.spacing[0], g.spacing[1], g.spacing[2] });
  for (std::size_t k = 0; k < g.size[2]; ++k)
  {
    for (std::size_t j = 0; j < g.size[1]; ++j)
    {
      for (std::size_t i = 0; i < g.size[0]; ++i)
      {
        const bender::Point3 p = g.IndexToPhysical({ { double(i), double(j), double(k) } });
        float& value = v.voxels[g.LinearIndex(i, j, k)];
        for (const auto& ball : balls)
        {
          const double d = std::sqrt(std::pow(p[0] - ball.first[0], 2) +
            std::pow(p[1] - ball.first[1], 2) + std::pow(p[2] - ball.first[2], 2));
          const double f = std::clamp(0.5 - (d - ball.second) / h, 0.0, 1.0);
          value = std::max(value, float(low + (high - low) * f));
        }
      }
    }
  }
  return v;
}

inline bender::ImageGeometry CubeGeometry(std::size_t n,
  double spacing,
  const bender::Point3& origin = { { 0, 0, 0 } })
{
  bender::ImageGeometry g;
  g.size = { { n, n, n } };
  g.spacing = { { spacing, spacing, spacing } };
  g.origin = origin;
  return g;
}

} // namespace bender_test

#endif
