#ifndef SliceViews_h
#define SliceViews_h

#include <QStringList>
#include <QWidget>

#include <vtkSmartPointer.h>

class BenderView;
class CursorOverlay;
class QComboBox;
class QLabel;
class QVTKOpenGLNativeWidget;
class vtkImageData;
class vtkPolyData;
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
/// The crosshair: one cursor point in LPS mm is shared by the three views: each view's slice
/// passes through it (the axial slice at its S coordinate, the coronal at P, the sagittal at
/// L), and each view draws the other two slices' traces through it as lines in their colours
/// (axial red, coronal green, sagittal yellow, as the pane titles). A left click or drag in a
/// view moves the cursor within that view's slice (the other two slices follow); the mouse
/// wheel, Up/Down and Page Up/Down move a view's slice one voxel at a time, and the cursor with
/// it. Shift+left drag sets the window/level; right drag zooms, middle drag pans, R frames the
/// view again. The line under the views gives the cursor's position in mm (patient letters:
/// "R 12.3, A 4.5, S 6.0 mm"), the intensity of the voxel under it and whether it is
/// segmented.
///
/// linkView() shows the cursor in the 3D view (CursorOverlay: a crosshair, optionally the
/// three slice planes' outlines; the combo box under the views chooses) and lets a Shift+click
/// on the surface there move the cursor, and the slices, to the point clicked.
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
  /// The cursor stays where it was when the new volume has the same box (a new mask), else
  /// it goes to the centre.
  void setVolume(vtkImageData* volume, vtkImageData* mask);
  bool hasVolume() const { return this->Volume != nullptr; }
  vtkImageData* volume() const;
  void render();

  /// Draws the cursor in `view` (its ribbon layer, above the surface) and lets a Shift+click
  /// on its surface move the cursor. Once, after both are made.
  void linkView(BenderView* view);
  /// The 3D view's cursor (null before linkView).
  CursorOverlay* cursorOverlay() const { return this->Overlay; }

  ///@{ The cursor (LPS mm).
  /// Moves the cursor (clamped to the volume's box) and the three slices through it; the
  /// crosshairs, the text and the 3D view follow. Nothing without a volume.
  void setCursor(const double position[3]);
  void cursor(double position[3]) const;
  /// The cursor under display pixel (x, y) of a view (VTK's pixels, origin bottom left),
  /// on that view's slice.
  void displayToCursor(int view, int x, int y, double position[3]) const;
  /// The intensity of the voxel nearest the cursor; false outside the volume.
  bool cursorValue(double& value) const;
  /// Whether the voxel nearest the cursor is segmented (false without a mask).
  bool cursorSegmented() const;
  /// The index of the voxel layer a view's slice passes through: the cursor's nearest voxel's
  /// index along the volume axis closest to the view's normal.
  int sliceIndex(int view) const;
  /// The text under the views ("R 12.3, A 4.5, S 6.0 mm: 213").
  QString cursorText() const;
  /// The crosshair lines of a view (two lines: the other views' slices through the cursor).
  vtkPolyData* crosshair(int view) const;
  ///@}

  ///@{ For tests and scripts.
  vtkRenderer* renderer(int view) const;
  vtkImageSlice* slice(int view) const;
  QVTKOpenGLNativeWidget* viewWidget(int view) const;
  /// The LPS coordinate (mm) of a view's slice along its axis (z axial, y coronal, x sagittal).
  double slicePosition(int view) const;
  /// Moves a view's slice, and the cursor, by `steps` voxels along its axis (clamped to the
  /// volume).
  void moveSlice(int view, int steps);
  /// Frames a view on the volume again (its pan and zoom, as R does), the slice staying at
  /// the cursor.
  void resetView(int view);
  /// The slice position as shown ("S 12.5 mm").
  QString positionText(int view) const;
  /// The patient directions at the edges: top, bottom, left, right ("A", "P", "R", "L").
  QStringList edgeLetters(int view) const;
  /// The volume's box in LPS (the voxels' outer faces).
  void volumeBounds(double bounds[6]) const;
  ///@}

  /// One view's VTK objects (internal).
  struct View;

signals:
  /// The cursor moved (LPS mm).
  void cursorMoved(double x, double y, double z);

private:
  void updateAnnotation(int view);
  void updateCrosshairs();

  View* Views[3];
  vtkSmartPointer<vtkImageData> Volume;
  vtkSmartPointer<vtkImageData> Mask;
  double Bounds[6] = { 0, -1, 0, -1, 0, -1 };
  double StepLength = 1.0;
  double Cursor[3] = { 0, 0, 0 };
  QLabel* CursorLabel = nullptr;
  QComboBox* CursorStyle = nullptr;
  CursorOverlay* Overlay = nullptr;
  BenderView* LinkedView = nullptr;
};

#endif
