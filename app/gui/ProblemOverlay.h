#ifndef ProblemOverlay_h
#define ProblemOverlay_h

#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkType.h>

class vtkActor;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkRenderer;

/// The triangles a check found wrong (the commit guard's flipped or crossing triangles), drawn
/// over the surface in the 3D view: filled in signal yellow with thick red edges, pulled towards
/// the camera so that they show on the surface they belong to. Hidden until Show().
class ProblemOverlay
{
public:
  explicit ProblemOverlay(vtkRenderer* renderer);
  ~ProblemOverlay();
  ProblemOverlay(const ProblemOverlay&) = delete;
  ProblemOverlay& operator=(const ProblemOverlay&) = delete;

  /// Draws `triangles` (copied); nothing drawn for null or empty.
  void Show(vtkPolyData* triangles);
  void Hide();
  bool IsShown() const;
  /// The triangles drawn now (for tests).
  vtkIdType GetNumberOfTriangles() const;
  vtkActor* GetActor() const;

private:
  vtkSmartPointer<vtkRenderer> Renderer; // held: the view may go first at window close
  vtkNew<vtkPolyDataMapper> Mapper;
  vtkNew<vtkActor> Actor;
  vtkNew<vtkPolyData> Triangles;
};

#endif
