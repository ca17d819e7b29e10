#ifndef SliceStyle_h
#define SliceStyle_h

#include <vtkInteractorStyleImage.h>

#include <functional>

/// The slice views' mouse: a left click or drag moves the cursor (through `MoveCursor`, with
/// the event's display position), Shift+left drag sets the window/level (the image style's
/// plain left drag); the rest is vtkInteractorStyleImage's (right zoom, middle pan).
class SliceStyle : public vtkInteractorStyleImage
{
public:
  static SliceStyle* New();
  vtkTypeMacro(SliceStyle, vtkInteractorStyleImage);

  /// Called with the display position (VTK's pixels) of a left press and of each move of a
  /// left drag.
  std::function<void(int, int)> MoveCursor;

  void OnLeftButtonDown() override;
  void OnMouseMove() override;
  void OnLeftButtonUp() override;

protected:
  SliceStyle() = default;
  ~SliceStyle() override = default;

private:
  SliceStyle(const SliceStyle&) = delete;
  void operator=(const SliceStyle&) = delete;
  /// A left drag that moves the cursor: the moves and the release are this style's.
  bool Dragging = false;
};

#endif
