#ifndef SliceViews_h
#define SliceViews_h

#include <QWidget>

#include <vtkSmartPointer.h>

class QVTKOpenGLNativeWidget;
class vtkImageData;
class vtkRenderer;

/// Axial, coronal and sagittal slices of the loaded volume with the segmentation overlaid in
/// translucent red. The volume is in LPS mm: axial looks from the feet (+S up the screen is
/// anterior), coronal from the front, sagittal from the left, radiological convention.
/// Mouse wheel / arrow keys move through the slices (vtkInteractorStyleImage).
class SliceViews : public QWidget
{
  Q_OBJECT
public:
  explicit SliceViews(QWidget* parent = nullptr);
  ~SliceViews() override;

  /// Shows `volume` (nullptr clears) and `mask` (optional overlay) at the volume's centre.
  void setVolume(vtkImageData* volume, vtkImageData* mask);
  bool hasVolume() const { return this->Volume != nullptr; }
  void render();

private:
  struct View;
  View* Views[3];
  vtkSmartPointer<vtkImageData> Volume;
  vtkSmartPointer<vtkImageData> Mask;
};

#endif
