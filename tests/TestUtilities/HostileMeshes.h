#ifndef bender_HostileMeshes_h
#define bender_HostileMeshes_h

// The reproducers of issue 25's file failures, generated so that each is visible next to the
// tests that use it (tests/Filters/CapRimTest, tests/cli_post/CliReproducersTest).

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace bendertest
{

/// The bytes of a binary STL of a closed cube 10 across, each face split into n x n squares of
/// two triangles (facet normals zero, as some exporters write them).
inline std::string CubeStl(int n)
{
  std::vector<std::array<std::array<float, 3>, 3>> tris;
  for (int axis = 0; axis < 3; ++axis)
  {
    for (int side = 0; side < 2; ++side)
    {
      for (int i = 0; i < n; ++i)
      {
        for (int j = 0; j < n; ++j)
        {
          const auto at = [&](int u, int v)
          {
            std::array<float, 3> p{};
            p[axis] = static_cast<float>(side * 10.0);
            p[(axis + 1) % 3] = static_cast<float>(u * 10.0 / n);
            p[(axis + 2) % 3] = static_cast<float>(v * 10.0 / n);
            return p;
          };
          const auto a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
          if (side == 1)
          {
            tris.push_back({ a, b, c });
            tris.push_back({ a, c, d });
          }
          else
          {
            tris.push_back({ a, d, c });
            tris.push_back({ a, c, b });
          }
        }
      }
    }
  }
  std::string bytes(80, ' ');
  const auto count = static_cast<std::uint32_t>(tris.size());
  bytes.append(reinterpret_cast<const char*>(&count), 4);
  for (const auto& t : tris)
  {
    const float normal[3] = { 0, 0, 0 };
    bytes.append(reinterpret_cast<const char*>(normal), 12);
    for (const auto& p : t)
    {
      bytes.append(reinterpret_cast<const char*>(p.data()), 12);
    }
    bytes.append(2, '\0');
  }
  return bytes;
}

/// The cube of CubeStl(2) with bits 3, 3 and 2 of three coordinate bytes flipped (a corner's 0
/// becomes 2.9e-42, a 5 becomes 327680, another 5 becomes 5.0005): still a readable STL, with
/// open boundary loops where corners no longer weld. Capping it crashed vtkDelaunay2D.
inline std::string CorruptedCubeStl()
{
  std::string bytes = CubeStl(2);
  bytes[471] = static_cast<char>(bytes[471] ^ 0x08);
  bytes[527] = static_cast<char>(bytes[527] ^ 0x08);
  bytes[751] = static_cast<char>(bytes[751] ^ 0x04);
  return bytes;
}

/// An OFF tetrahedron open at one face with the coordinate `far` (text, e.g. "-1e308").
inline std::string OpenTetrahedronOff(const std::string& far)
{
  return "OFF\n4 3 0\n0 0 0\n" + far + " 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n";
}

} // namespace bendertest

#endif
