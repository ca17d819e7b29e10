#ifndef ProblemOverlay_h
#define ProblemOverlay_h

#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <string>

class vtkActor;
class vtkBillboardTextActor3D;
class vtkSphereSource;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkRenderer;

/// The triangles a check found wrong (the commit guard's flipped or crossing triangles), drawn
/// over the surface in the 3D view: filled in signal yellow with thick red edges, pulled towards
/// the camera so that they show on the surface they belong to. And the lumen guard's narrowest
/// point: a ball of the lumen's size with a label, in `topLayer` (seen through the vessel).
/// Hidden until Show() / ShowNarrowing().
class ProblemOverlay
{
public:
  explicit ProblemOverlay(vtkRenderer* renderer, vtkRenderer* topLayer = nullptr);
  ~ProblemOverlay();
  ProblemOverlay(const ProblemOverlay&) = delete;
  ProblemOverlay& operator=(const ProblemOverlay&) = delete;

  /// Draws `triangles` (copied); nothing drawn for null or empty.
  void Show(vtkPolyData* triangles);
  /// Marks where a branch is narrowest (`radius`: its minimal inscribed radius) with `label`.
  void ShowNarrowing(const double point[3], double radius, const std::string& label);
  /// Hides the triangles and the marker.
  void Hide();
  bool IsNarrowingShown() const;
  /// The marker's position and label (for tests); false when not shown.
  bool GetNarrowing(double point[3], std::string& label) const;
  bool IsShown() const;
  /// The triangles drawn now (for tests).
  vtkIdType GetNumberOfTriangles() const;
  vtkActor* GetActor() const;

private:
  vtkSmartPointer<vtkRenderer> Renderer; // held: the view may go first at window close
  vtkSmartPointer<vtkRenderer> TopLayer;
  vtkNew<vtkPolyDataMapper> Mapper;
  vtkNew<vtkActor> Actor;
  vtkNew<vtkPolyData> Triangles;
  vtkNew<vtkSphereSource> Ball;
  vtkNew<vtkPolyDataMapper> BallMapper;
  vtkNew<vtkActor> BallActor;
  vtkNew<vtkBillboardTextActor3D> Label;
};

#endif
