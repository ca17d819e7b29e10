#ifndef DataPanel_h
#define DataPanel_h

#include <QWidget>

class MainActions;
class QLabel;

namespace bender
{
class BenderSession;
class SegmentationSession;
}

/// The Data panel: open, demo, and what is loaded (surface points and triangles, warps
/// committed, frame; the volume).
class DataPanel : public QWidget
{
  Q_OBJECT
public:
  DataPanel(MainActions* actions, QWidget* parent = nullptr);
  void showState(const bender::BenderSession& session, const bender::SegmentationSession& volumes);

private:
  QLabel* Info;
};

#endif
