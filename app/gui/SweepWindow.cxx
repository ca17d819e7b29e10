#include "SweepWindow.h"

#include "FlowViews.h"
#include "SweepCandidateTable.h"
#include "SweepPlotView.h"

#include "BenderErrors.h"
#include "FlowStudy.h"

#include <QLabel>
#include <QSplitter>
#include <QVBoxLayout>

#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkRenderer.h>

namespace
{
/// "c03, fraction 0.75" / "c01, plan b.json".
QString Describe(const bender::SweepRow& row)
{
  const QString value = row.parameter == "plan" ? QString::fromStdString(row.planName)
                                                : QString::number(row.value, 'g', 4);
  return QString("%1, %2 %3")
    .arg(QString::fromStdString(row.id), QString::fromStdString(row.parameter), value);
}
} // namespace

SweepWindow::SweepWindow(QWidget* parent)
  : QWidget(parent, Qt::Window)
{
  this->setObjectName("sweepWindow");
  this->setWindowTitle("Bender - sweep");
  this->resize(1200, 900);
  auto* layout = new QVBoxLayout(this);
  auto* split = new QSplitter(Qt::Vertical, this);
  this->Plot = new SweepPlotView(split);
  this->Table = new SweepCandidateTable(split);
  this->Views = new FlowViews(split);
  split->addWidget(this->Plot);
  split->addWidget(this->Table);
  split->addWidget(this->Views);
  split->setStretchFactor(0, 2);
  split->setStretchFactor(1, 2);
  split->setStretchFactor(2, 3);
  layout->addWidget(split, 1);
  this->Caption = new QLabel(this);
  this->Caption->setObjectName("sweepCaption");
  this->Caption->setWordWrap(true);
  this->Caption->setTextInteractionFlags(Qt::TextSelectableByMouse);
  layout->addWidget(this->Caption);
  connect(this->Table, &SweepCandidateTable::candidateChosen, this, &SweepWindow::showCandidate);
}

SweepWindow::~SweepWindow() = default;

void SweepWindow::setSweep(const bender::SweepFolder& sweep)
{
  this->Sweep = sweep;
  this->Shown.clear();
  this->Original = nullptr;
  this->Framed = false;
  this->setWindowTitle("Bender - sweep: " + QString::fromStdString(sweep.folder));
  this->Table->setRows(sweep.rows, sweep.parameter);
  this->Plot->setRows(sweep.rows, sweep.parameter);
  this->Caption->setText("Choose a candidate in the table to see it beside the original.");
  for (std::size_t i = 0; i < sweep.rows.size(); ++i)
  {
    if (sweep.rows[i].state == "solved" && !sweep.rows[i].original)
    {
      this->Table->setCurrentCell(static_cast<int>(i), 0); // candidateChosen shows it
      return;
    }
  }
  QString problem;
  this->Views->setSurfaces(this->originalSurface(problem),
    nullptr,
    this->ViewRenderer ? this->ViewRenderer->GetActiveCamera() : nullptr);
  if (!problem.isEmpty())
  {
    this->Caption->setText("No candidate solved to show: " + problem);
  }
}

vtkPolyData* SweepWindow::originalSurface(QString& problem)
{
  if (this->Original)
  {
    return this->Original;
  }
  const bender::SweepRow* original = bender::SweepOriginalRow(this->Sweep.rows);
  if (!original)
  {
    problem = "this sweep has no original among its candidates";
    return nullptr;
  }
  if (original->state != "solved")
  {
    problem = "the original (" + QString::fromStdString(original->id) + ") is not solved";
    return nullptr;
  }
  try
  {
    this->Original = bender::ReadFlowShape(
      bender::SweepCaseFolder(this->Sweep, *original), bender::FlowShape::Original)
                       .surface;
  }
  catch (const bender::InputError& e)
  {
    problem = e.what();
  }
  return this->Original;
}

bool SweepWindow::showCandidate(int index)
{
  if (index < 0 || index >= static_cast<int>(this->Sweep.rows.size()))
  {
    return false;
  }
  const bender::SweepRow& row = this->Sweep.rows[static_cast<std::size_t>(index)];
  this->Plot->setRows(this->Sweep.rows, this->Sweep.parameter, row.id);
  QString problem;
  vtkPolyData* original = this->originalSurface(problem);
  vtkSmartPointer<vtkPolyData> candidate;
  if (row.state != "solved")
  {
    problem = QString::fromStdString(row.id) + " is " + QString::fromStdString(row.state) +
      (row.reason.empty() ? QString() : ": " + QString::fromStdString(row.reason));
  }
  else
  {
    try
    {
      candidate =
        bender::ReadFlowShape(bender::SweepCaseFolder(this->Sweep, row), bender::FlowShape::Current)
          .surface;
    }
    catch (const bender::InputError& e)
    {
      problem = e.what();
    }
  }
  const bender::SweepRow* first = bender::SweepOriginalRow(this->Sweep.rows);
  this->Views->setTitles(
    first ? "Original (" + QString::fromStdString(first->id) + ")" : QString("Original"),
    Describe(row));
  // Framed as the main view looks the first time; then the viewpoint the user chose is kept.
  vtkNew<vtkCamera> kept;
  kept->DeepCopy(this->Views->renderer(0)->GetActiveCamera());
  this->Views->setSurfaces(
    original, candidate, this->ViewRenderer ? this->ViewRenderer->GetActiveCamera() : nullptr);
  if (this->Framed)
  {
    for (int i = 0; i < 2; ++i)
    {
      this->Views->renderer(i)->GetActiveCamera()->DeepCopy(kept);
      this->Views->renderer(i)->ResetCameraClippingRange();
    }
  }
  this->Framed = this->Framed || original || candidate;
  this->Views->setStreamlines(nullptr, nullptr); // renders both views
  this->Shown = candidate ? row.id : std::string();
  this->Caption->setText(problem.isEmpty()
      ? QString("%1 beside the original; the views are linked and share one colour scale.")
          .arg(Describe(row))
      : "Nothing to show for " + Describe(row) + ": " + problem);
  return problem.isEmpty();
}
