#ifndef SliceView_h
#define SliceView_h

#include "SliceStyle.h"
#include "SliceViews.h"

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCornerAnnotation.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkImageResliceMapper.h>
#include <vtkImageSlice.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderer.h>

class vtkLookupTable;

/// One of the three slice views of SliceViews (internal): its widget and render window, the
/// volume's slice and the mask's overlay (resliced at the camera's focal point, facing the
/// camera), the crosshair, the corner annotation, its mouse (SliceStyle) and the observers of
/// its wheel and keys (a slice step: SliceViews::moveSlice; R: SliceViews::resetView).
struct SliceViews::View
{
  /// Makes view `index` (SliceViews::Orientation) of `owner` as a child widget of it; the
  /// overlay draws the mask through `maskColours`.
  View(SliceViews* owner, int index, vtkLookupTable* maskColours);

  /// Zoomed to show the whole volume's section in this view, centred; the slice stays.
  void fit();
  /// Shows `volume` (its window/level from its robust range) and `mask` (may be null), the
  /// camera framed on the centre of `bounds` and sliced through `cursor` (LPS mm).
  void show(vtkImageData* volume,
    vtkImageData* mask,
    const double bounds[6],
    const double cursor[3]);
  /// The camera on `centre`, looking along the view's direction from its current distance.
  void lookAt(const double centre[3], double distance);

  SliceViews* owner = nullptr;
  int index = 0;
  QVTKOpenGLNativeWidget* widget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkImageResliceMapper> mapper;
  vtkNew<vtkImageSlice> slice;
  vtkNew<vtkImageResliceMapper> overlayMapper;
  vtkNew<vtkImageSlice> overlay;
  vtkNew<SliceStyle> style;
  vtkNew<vtkCornerAnnotation> annotation;
  vtkNew<vtkPolyData> crosshairData;
  vtkNew<vtkPolyDataMapper> crosshairMapper;
  vtkNew<vtkActor> crosshair;
  vtkNew<vtkCallbackCommand> inputObserver;
  vtkNew<vtkCallbackCommand> renderObserver;
  double viewDirection[3] = { 0, 0, 1 };
  double viewUp[3] = { 0, 1, 0 };
  int fittedSize[2] = { 0, 0 };

private:
  /// The wheel, Up/Down, Page Up/Down (a slice step) and the keys of vtkInteractorStyleImage
  /// that would leave the patient frame (x, y, z, r).
  static void OnInput(vtkObject* caller, unsigned long event, void* clientData, void*);
  /// Before each frame: fitted again after a resize, the annotation brought up to date.
  static void BeforeRender(vtkObject*, unsigned long, void* clientData, void*);
};

#endif
