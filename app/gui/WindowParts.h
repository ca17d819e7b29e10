#ifndef WindowParts_h
#define WindowParts_h

namespace bender
{
class BenderSession;
class SegmentationSession;
}
class BendPanel;
class BenderView;
class GestureController;
class MainActions;
class QWidget;
class SegmentPanel;
class WorkRunner;

/// The parts of a window that the controllers bringing data in (FileOpener, AutosaveController)
/// work with: the sessions, the worker, the shared actions, the 3D view, the gesture, the Bend
/// and Segment panels, and the window itself (the parent of dialogs). MainWindow owns them all
/// and outlives the controllers.
struct WindowParts
{
  bender::BenderSession& session;
  bender::SegmentationSession& segmentation;
  WorkRunner* worker;
  MainActions* actions;
  BenderView* view;
  GestureController* gesture;
  BendPanel* bend;
  SegmentPanel* segment;
  QWidget* window;
};

#endif
