#ifndef FlowReportSaver_h
#define FlowReportSaver_h

#include "WarpPlan.h"

#include <QObject>
#include <QString>
#include <QStringList>

#include <string>

namespace bender
{
class BenderSession;
}
class QWidget;
class WorkRunner;

/// The Flow panel's "Save report" (issue 23, "a report a surgeon brings to the planning
/// meeting"): the report of app/report (WriteFlowReport, the PDF bender-cli compare writes) of
/// the two cases on screen, a PNG of each of its pictures and the plan that made the candidate,
/// into a folder the user picks. Files of an earlier report there are replaced only when the
/// user says so. The work (the two cases read and compared, the centerlines of both shapes,
/// the pictures, the PDF) runs on the window's worker: the window keeps drawing.
class FlowReportSaver : public QObject
{
  Q_OBJECT
public:
  /// What the report is of: the two case folders and the plan of their run.
  struct Source
  {
    std::string caseA; ///< the original's case folder
    std::string caseB; ///< the current shape's case folder
    bender::WarpPlan plan;
  };

  FlowReportSaver(bender::BenderSession& session, WorkRunner* worker, QWidget* dialogParent);

  /// The report's PDF in `folder`.
  static QString pdfIn(const QString& folder);
  /// Every file a report writes into `folder`: the PDF, the pictures, the plan.
  static QStringList filesIn(const QString& folder);

  /// Asks for a folder (the last one used first), then saves there.
  void saveAsked(const Source& source);
  /// Saves into `folder` (made when missing), asking first when a file of the report is there
  /// already. False when the user keeps the files there, the worker is busy or `source` has no
  /// cases: nothing is written.
  bool save(const QString& folder, const Source& source);

signals:
  /// A save ended: the PDF written (ok), or failed with its message in the status bar.
  void saved(bool ok, const QString& pdf);

private:
  bool replaceAllowed(const QString& folder) const;

  bender::BenderSession& Session;
  WorkRunner* Worker;
  QWidget* DialogParent;
};

#endif
