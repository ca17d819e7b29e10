#ifndef bender_CfdStageTimes_h
#define bender_CfdStageTimes_h

// How long each stage of a run took (issue 23, "Speed"): the Allrun's steps timed by the wall
// clock as their "bender Allrun: PROGRAM ..." lines arrive, grouped into the stages a user
// waits for: mesh, layers, solve and map. snappyHexMesh meshes and adds the layers in one
// program; its wall time is split between the two by its own clock (the "Mesh refined in",
// "Mesh snapped in" and "Layers added in" lines of log.snappyHexMesh).

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace bender
{

/// Wall-clock seconds of a run's stages.
struct CfdStageTimes
{
  /// blockMesh, surfaceFeatureExtract, snappyHexMesh's refinement and snapping, checkMesh.
  double mesh = 0.0;
  /// snappyHexMesh's addLayers (its share of snappyHexMesh's wall time).
  double layers = 0.0;
  /// decomposePar, simpleFoam (serial or under mpirun), reconstructPar.
  double solve = 0.0;
  /// MapCfdResults: the case read back and mapped onto the surface, CASE/results written.
  double map = 0.0;
  /// Each Allrun step in order: the program ("snappyHexMesh", "mpirun") and its seconds.
  std::vector<std::pair<std::string, double>> steps;

  double Total() const { return this->mesh + this->layers + this->solve + this->map; }
};

/// snappyHexMesh's phases by its own clock, seconds (0 when its log does not say).
struct SnappyPhaseTimes
{
  double refine = 0.0;
  double snap = 0.0;
  double layers = 0.0;
};

/// Reads the phase times from the text of log.snappyHexMesh (the last of each line).
SnappyPhaseTimes ParseSnappyPhaseTimes(const std::string& log);

/// Times the Allrun's steps from its output lines: Line() at each line, Finish() when the
/// Allrun has ended. A line "bender Allrun: PROGRAM ARGS" ends the step before it and starts
/// PROGRAM's; its failure lines ("... failed, see ...", "checkMesh found problems") do not.
class CfdStepClock
{
public:
  void Line(const std::string& line);
  void Finish();
  /// The steps timed so far, in order.
  const std::vector<std::pair<std::string, double>>& Steps() const { return this->Timed; }

private:
  using Clock = std::chrono::steady_clock;
  std::vector<std::pair<std::string, double>> Timed;
  std::string Current;
  Clock::time_point Started;
};

/// The stages of a run from its timed steps and the text of log.snappyHexMesh (empty when the
/// mesh was not made in this run); map is left 0.
CfdStageTimes GroupCfdStages(const std::vector<std::pair<std::string, double>>& steps,
  const std::string& snappyLog);

/// "mesh 12.3 s, layers 4.1 s, solve 61.0 s, map 2.9 s".
std::string FormatCfdStageTimes(const CfdStageTimes& times);

} // namespace bender

#endif
