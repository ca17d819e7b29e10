#ifndef bender_LevelOfDetail_h
#define bender_LevelOfDetail_h

#include <vtkPolyData.h>
#include <vtkPolyDataAlgorithm.h>
#include <vtkSmartPointer.h>

namespace bender
{

/// The decimated copy drawn (and warped while dragging) instead of a surface of many
/// triangles: vtkQuadricClustering with bins of about 1/100 of the surface's size, points
/// placed by the bins' quadrics (42k triangles for the 1.3 M-triangle benchmark vessel).
/// An empty surface for none or an empty one; the surface itself (shallow copy) when a point
/// is not finite.
vtkSmartPointer<vtkPolyData> MakeLevelOfDetail(vtkPolyData* surface);

} // namespace bender

/// The level of detail of the committed surface (its input): the decimated copy, made when
/// the output is pulled and the input changed, or the copy a release job made for this input.
class vtkBenderLevelOfDetailSource : public vtkPolyDataAlgorithm
{
public:
  static vtkBenderLevelOfDetailSource* New();
  vtkTypeMacro(vtkBenderLevelOfDetailSource, vtkPolyDataAlgorithm);
  /// `copy` is the decimated copy of `input` (in its present state): used instead of
  /// decimating again.
  void SetPrepared(vtkPolyData* input, vtkPolyData* copy);
  /// How many copies RequestData decimated (non-empty inputs only).
  long long GetBuildCount() const { return this->Builds; }

protected:
  vtkBenderLevelOfDetailSource() = default;
  int RequestData(vtkInformation*,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

private:
  vtkBenderLevelOfDetailSource(const vtkBenderLevelOfDetailSource&) = delete;
  void operator=(const vtkBenderLevelOfDetailSource&) = delete;
  vtkPolyData* PreparedFor = nullptr; // identity only
  vtkMTimeType PreparedTime = 0;
  vtkSmartPointer<vtkPolyData> Prepared;
  long long Builds = 0;
};

#endif
