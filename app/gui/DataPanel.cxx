#include "DataPanel.h"

#include "BenderSession.h"
#include "MainActions.h"
#include "PlanSummary.h"
#include "SegmentationSession.h"
#include "StringUtil.h"

#include <QFileInfo>
#include <QLabel>
#include <QToolButton>
#include <QVBoxLayout>

#include <vtkPolyData.h>

DataPanel::DataPanel(MainActions* actions, QWidget* parent)
  : QWidget(parent)
{
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(ActionButton(actions->Open, this, "openButton"));
  layout->addWidget(ActionButton(actions->Demo, this, "demoButton"));
  layout->addWidget(new QLabel("Or drop files on the window.", this));
  this->Info = new QLabel("No data", this);
  this->Info->setToolTip("What is loaded: the surface (points, triangles), the warps committed, "
                         "the volume, and the frame (LPS, mm)");
  this->Info->setObjectName("dataInfo");
  this->Info->setWordWrap(true);
  layout->addWidget(this->Info);
  layout->addStretch(1);
}

void DataPanel::showState(const bender::BenderSession& session,
  const bender::SegmentationSession& volumes)
{
  QString text;
  if (session.HasSurface())
  {
    vtkPolyData* surface = session.GetSurface();
    text = QString("%1\n%2 points, %3 triangles (LPS mm)\n%4")
             .arg(QString::fromStdString(session.GetSurfaceName()))
             .arg(surface->GetNumberOfPoints())
             .arg(surface->GetNumberOfPolys())
             .arg(QString::fromStdString(bender::PlanSummary(session.GetPlan())));
  }
  if (volumes.HasVolume())
  {
    const auto& size = volumes.GetVolume()->geometry.size;
    text += QString("%1Volume %2: %3x%4x%5%6")
              .arg(text.isEmpty() ? "" : "\n\n")
              .arg(QFileInfo(QString::fromStdString(volumes.GetVolumeName())).fileName())
              .arg(size[0])
              .arg(size[1])
              .arg(size[2])
              .arg(volumes.GetMask() ? ", segmented" : "");
  }
  this->Info->setText(text.isEmpty() ? "No data" : text);
}
