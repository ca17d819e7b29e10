#ifndef FlowViews_h
#define FlowViews_h

#include <QWidget>

#include <vtkNew.h>
#include <vtkSmartPointer.h>

class QCheckBox;
class QComboBox;
class QLabel;
class QVTKOpenGLNativeWidget;
class vtkActor;
class vtkCamera;
class vtkGenericOpenGLRenderWindow;
class vtkLookupTable;
class vtkObject;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkRenderer;
class vtkScalarBarActor;

/// The original and the current shape side by side, coloured by the same field on the same
/// colour scale (one lookup table, its scalar bar with the unit in the right view): pressure
/// (Pa, relative to the outlets' mean) or wall shear stress magnitude (Pa). The two cameras are
/// linked: turning, panning or zooming one view moves the other to the same viewpoint.
class FlowViews : public QWidget
{
  Q_OBJECT
public:
  /// The fields, in the combo box's order.
  enum class Field
  {
    Pressure,
    WallShearStress
  };

  explicit FlowViews(QWidget* parent = nullptr);
  ~FlowViews() override;

  /// Shows the two results surfaces (results/surface.vtp: point data Pressure and
  /// WallShearStressMagnitude) and frames both, looking as `like` looks (the main view's
  /// camera: the shapes seen as they were bent), from the front (anterior, LPS) without one.
  void setSurfaces(vtkPolyData* original, vtkPolyData* current, vtkCamera* like = nullptr);
  /// The streamlines of each shape (FlowStreamlines; null: none), drawn when the Streamlines box
  /// is ticked, through the surfaces made translucent.
  void setStreamlines(vtkPolyData* original, vtkPolyData* current);
  /// The titles above the two views ("Original", "Current shape" until set).
  void setTitles(const QString& left, const QString& right);
  void setStreamlinesShown(bool shown);
  bool streamlinesShown() const;
  void setField(Field field);
  Field field() const;
  /// The shared colour range of the field shown, over both surfaces.
  void range(double range[2]) const;
  /// The scalar bar's title ("Pressure (Pa)").
  QString scaleTitle() const;

  /// view 0 the original, 1 the current shape.
  QVTKOpenGLNativeWidget* view(int which) const;
  vtkRenderer* renderer(int which) const;
  vtkPolyDataMapper* mapper(int which) const;
  void render();

private:
  /// Copies the camera of view `from` to the other view and renders it.
  void follow(int from);
  void showField();

  struct View
  {
    QVTKOpenGLNativeWidget* widget = nullptr;
    QLabel* title = nullptr;
    vtkNew<vtkGenericOpenGLRenderWindow> window;
    vtkNew<vtkRenderer> renderer;
    vtkNew<vtkPolyDataMapper> mapper;
    vtkNew<vtkActor> actor;
    vtkSmartPointer<vtkPolyData> surface;
    vtkNew<vtkPolyDataMapper> lineMapper;
    vtkNew<vtkActor> lines;
  };
  View Views[2];
  vtkNew<vtkLookupTable> Colours;
  vtkNew<vtkScalarBarActor> ScaleBar;
  QComboBox* FieldChoice = nullptr;
  QCheckBox* Streamlines = nullptr;
  bool Following = false;
};

#endif
