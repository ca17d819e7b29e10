// bender_sweep_test_tube PATH: writes the sweep tests' tube (SweepTestTube.h) to PATH, in the
// mesh format its extension names, for the slurm test's shell script.

#include "BenderErrors.h"
#include "MeshIO.h"
#include "SweepTestTube.h"

#include <cstdio>

int main(int argc, char** argv)
{
  if (argc != 2)
  {
    std::fprintf(stderr, "usage: %s PATH\n", argv[0]);
    return 2;
  }
  try
  {
    bender::WriteMesh(bendertest::SweepTestTube(), argv[1]);
  }
  catch (const bender::Error& e)
  {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
