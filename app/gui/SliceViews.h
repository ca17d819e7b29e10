#ifndef SliceViews_h
#define SliceViews_h

#include <QStringList>
#include <QWidget>

#include <vtkSmartPointer.h>

class QLabel;
class QVTKOpenGLNativeWidget;
class vtkImageData;
class vtkObject;
class vtkImageSlice;
class vtkRenderer;

/// Axial, coronal and sagittal slices of the loaded volume with the segmentation overlaid in
/// translucent red. The volume is in LPS mm, with its own direction matrix (oblique or flipped
/// acquisitions, NIfTI's RAS-stored volumes): the slices are drawn in the patient frame through
/// the volume's index-to-LPS matrix, so that every view shows the whole volume whatever its
/// direction. Axial looks from the feet (anterior up), coronal from the front, sagittal from
/// the left, radiological convention (the patient's left on the screen's right in axial and
/// coronal). Each view shows its slice position in mm (the LPS coordinate along its axis, with
/// its letter: "S 12.5 mm") and the patient direction at each edge (A/P, R/L, S/I).
/// Mouse wheel, Up/Down and Page Up/Down move through the slices one voxel at a time; the left
/// button drags the window/level.
class SliceViews : public QWidget
{
  Q_OBJECT
public:
  enum Orientation
  {
    Axial = 0,
    Coronal,
    Sagittal
  };

  explicit SliceViews(QWidget* parent = nullptr);
  ~SliceViews() override;

  /// Shows `volume` (nullptr clears) and `mask` (optional overlay) at the volume's centre.
  void setVolume(vtkImageData* volume, vtkImageData* mask);
  bool hasVolume() const { return this->Volume != nullptr; }
  void render();

  ///@{ For tests and scripts.
  vtkRenderer* renderer(int view) const;
  vtkImageSlice* slice(int view) const;
  QVTKOpenGLNativeWidget* viewWidget(int view) const;
  /// The LPS coordinate (mm) of a view's slice along its axis (z axial, y coronal, x sagittal).
  double slicePosition(int view) const;
  /// Moves a view's slice by `steps` voxels along its axis (clamped to the volume).
  void moveSlice(int view, int steps);
  /// The slice position as shown ("S 12.5 mm").
  QString positionText(int view) const;
  /// The patient directions at the edges: top, bottom, left, right ("A", "P", "R", "L").
  QStringList edgeLetters(int view) const;
  /// The volume's box in LPS (the voxels' outer faces).
  void volumeBounds(double bounds[6]) const;
  ///@}

  /// One view's VTK objects (internal).
  struct View;

private:
  void updateAnnotation(int view);
  static void BeforeRender(vtkObject*, unsigned long, void* clientData, void*);

  View* Views[3];
  vtkSmartPointer<vtkImageData> Volume;
  vtkSmartPointer<vtkImageData> Mask;
  double Bounds[6] = { 0, -1, 0, -1, 0, -1 };
  double StepLength = 1.0;
};

#endif
