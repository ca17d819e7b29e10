#include "SliceViews.h"

#include "BenderView.h"
#include "CursorOverlay.h"
#include "SliceGeometry.h"
#include "SliceView.h"

#include <QComboBox>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QStringList>

#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkImageData.h>
#include <vtkLookupTable.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>

SliceViews::SliceViews(QWidget* parent)
  : QWidget(parent)
{
  auto* layout = new QGridLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  vtkNew<vtkLookupTable> maskColours;
  maskColours->SetNumberOfTableValues(2);
  maskColours->SetTableRange(0, 1);
  maskColours->SetTableValue(0, 0, 0, 0, 0);
  maskColours->SetTableValue(1, 1, 0.2, 0.2, 0.45);
  maskColours->Build();
  for (int i = 0; i < 3; ++i)
  {
    auto* view = new View(this, i, maskColours);
    this->Views[i] = view;
    auto* label = new QLabel(SliceNames[i], this);
    label->setStyleSheet(QString("color: rgb(%1, %2, %3); font-weight: bold;")
                           .arg(SliceColours[i][0])
                           .arg(SliceColours[i][1])
                           .arg(SliceColours[i][2]));
    layout->addWidget(label, 0, i);
    layout->addWidget(view->widget, 1, i);
  }
  layout->setRowStretch(1, 1);
  auto* row = new QHBoxLayout;
  this->CursorLabel = new QLabel("Cursor: no volume", this);
  this->CursorLabel->setObjectName("sliceCursor");
  this->CursorLabel->setToolTip("The cursor shared by the slice views and the 3D view (LPS "
                                "model coordinates, mm), the intensity of the voxel under it "
                                "and whether it is segmented");
  this->CursorLabel->setTextInteractionFlags(Qt::TextSelectableByMouse);
  row->addWidget(this->CursorLabel, 1);
  row->addWidget(new QLabel("In the 3D view:", this));
  this->CursorStyle = new QComboBox(this);
  this->CursorStyle->setObjectName("sliceCursorStyle");
  this->CursorStyle->addItem("no cursor");
  this->CursorStyle->addItem("crosshair");
  this->CursorStyle->addItem("crosshair and slice planes");
  this->CursorStyle->setCurrentIndex(CursorOverlay::Crosshair);
  this->CursorStyle->setToolTip("How the cursor is drawn in the 3D view; there, Shift+click on "
                                "the surface moves the cursor and the slices to that point");
  row->addWidget(this->CursorStyle);
  layout->addLayout(row, 2, 0, 1, 3);
  connect(this->CursorStyle,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    [this](int index)
    {
      if (!this->Overlay)
        return;
      this->Overlay->setStyle(static_cast<CursorOverlay::Style>(index));
      if (this->LinkedView)
        this->LinkedView->render();
    });
}

void SliceViews::linkView(BenderView* view)
{
  if (this->Overlay || !view)
  {
    return;
  }
  this->LinkedView = view;
  this->Overlay =
    new CursorOverlay(view->ribbonRenderer(), view->renderer(), view->surfaceActor(), this);
  this->Overlay->setBusy([view]() { return view->isPicking(); });
  this->Overlay->setStyle(static_cast<CursorOverlay::Style>(this->CursorStyle->currentIndex()));
  const double none[6] = { 0, -1, 0, -1, 0, -1 };
  this->Overlay->setBounds(this->Volume ? this->Bounds : none);
  this->Overlay->setPosition(this->Cursor);
  connect(this->Overlay,
    &CursorOverlay::picked,
    this,
    [this](double x, double y, double z)
    {
      const double position[3] = { x, y, z };
      this->setCursor(position);
    });
}

SliceViews::~SliceViews()
{
  for (View* view : this->Views)
  {
    delete view;
  }
}

void SliceViews::volumeBounds(double bounds[6]) const
{
  std::copy(this->Bounds, this->Bounds + 6, bounds);
}

void SliceViews::setVolume(vtkImageData* volume, vtkImageData* mask)
{
  const double previous[6] = { this->Bounds[0],
    this->Bounds[1],
    this->Bounds[2],
    this->Bounds[3],
    this->Bounds[4],
    this->Bounds[5] };
  const bool hadVolume = this->Volume != nullptr;
  this->Volume = volume;
  this->Mask = mask;
  if (volume)
  {
    VoxelBox(volume, this->Bounds);
    const double* spacing = volume->GetSpacing();
    this->StepLength = std::max(1e-6, *std::min_element(spacing, spacing + 3));
    if (!hadVolume || !std::equal(previous, previous + 6, this->Bounds))
    {
      for (int axis = 0; axis < 3; ++axis)
      {
        this->Cursor[axis] = 0.5 * (this->Bounds[2 * axis] + this->Bounds[2 * axis + 1]);
      }
    }
  }
  for (View* view : this->Views)
  {
    view->show(volume, mask, this->Bounds, this->Cursor);
  }
  if (this->Overlay)
  {
    const double none[6] = { 0, -1, 0, -1, 0, -1 };
    this->Overlay->setBounds(volume ? this->Bounds : none);
    this->Overlay->setPosition(this->Cursor);
  }
  this->updateCrosshairs();
  this->render();
  if (this->LinkedView)
  {
    this->LinkedView->render();
  }
}

vtkRenderer* SliceViews::renderer(int view) const
{
  return this->Views[std::max(0, std::min(2, view))]->renderer;
}

vtkImageSlice* SliceViews::slice(int view) const
{
  return this->Views[std::max(0, std::min(2, view))]->slice;
}

QVTKOpenGLNativeWidget* SliceViews::viewWidget(int view) const
{
  return this->Views[std::max(0, std::min(2, view))]->widget;
}

double SliceViews::slicePosition(int view) const
{
  const View* v = this->Views[std::max(0, std::min(2, view))];
  const double* focal = v->renderer->GetActiveCamera()->GetFocalPoint();
  return focal[SliceAxis(view)];
}

void SliceViews::moveSlice(int view, int steps)
{
  if (!this->Volume)
  {
    return;
  }
  const View* v = this->Views[std::max(0, std::min(2, view))];
  const int axis = SliceAxis(v->index);
  // Forward (wheel up) goes towards the viewer's side: S, A, L.
  const double step = -steps * this->StepLength;
  double position[3] = { this->Cursor[0], this->Cursor[1], this->Cursor[2] };
  position[axis] += step * v->viewDirection[axis];
  this->setCursor(position);
}

void SliceViews::resetView(int view)
{
  if (!this->Volume)
  {
    return;
  }
  View* v = this->Views[std::max(0, std::min(2, view))];
  const int axis = SliceAxis(v->index);
  double centre[3];
  for (int a = 0; a < 3; ++a)
  {
    centre[a] = a == axis ? this->Cursor[a] : 0.5 * (this->Bounds[2 * a] + this->Bounds[2 * a + 1]);
  }
  v->lookAt(centre, v->renderer->GetActiveCamera()->GetDistance());
  v->fit();
  v->window->Render();
}

void SliceViews::setCursor(const double position[3])
{
  if (!this->Volume)
  {
    return;
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    const double p = std::isfinite(position[axis]) ? position[axis] : this->Cursor[axis];
    this->Cursor[axis] = std::min(this->Bounds[2 * axis + 1], std::max(this->Bounds[2 * axis], p));
  }
  // Each view's slice through the cursor: its camera slides along its normal (the pan and the
  // zoom stay).
  for (View* v : this->Views)
  {
    const int axis = SliceAxis(v->index);
    vtkCamera* camera = v->renderer->GetActiveCamera();
    double focal[3], eye[3];
    camera->GetFocalPoint(focal);
    camera->GetPosition(eye);
    const double shift = this->Cursor[axis] - focal[axis];
    focal[axis] += shift;
    eye[axis] += shift;
    camera->SetFocalPoint(focal);
    camera->SetPosition(eye);
  }
  if (this->Overlay)
  {
    this->Overlay->setPosition(this->Cursor);
  }
  this->updateCrosshairs();
  this->render();
  if (this->LinkedView)
  {
    this->LinkedView->render();
  }
  emit this->cursorMoved(this->Cursor[0], this->Cursor[1], this->Cursor[2]);
}

vtkImageData* SliceViews::volume() const
{
  return this->Volume;
}

void SliceViews::cursor(double position[3]) const
{
  std::copy(this->Cursor, this->Cursor + 3, position);
}

void SliceViews::displayToCursor(int view, int x, int y, double position[3]) const
{
  const View* v = this->Views[std::max(0, std::min(2, view))];
  // A parallel projection: the display point on the focal plane is the point in the slice.
  vtkRenderer* renderer = v->renderer;
  renderer->SetDisplayPoint(x, y, 0.5);
  renderer->DisplayToWorld();
  double world[4];
  renderer->GetWorldPoint(world);
  const double w = world[3] != 0.0 ? world[3] : 1.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    position[axis] = world[axis] / w;
  }
  position[SliceAxis(v->index)] = this->Cursor[SliceAxis(v->index)];
}

bool SliceViews::cursorValue(double& value) const
{
  int ijk[3];
  if (!NearestVoxel(this->Volume, this->Cursor, ijk) || !this->Volume->GetPointData()->GetScalars())
  {
    return false;
  }
  value = this->Volume->GetScalarComponentAsDouble(ijk[0], ijk[1], ijk[2], 0);
  return true;
}

bool SliceViews::cursorSegmented() const
{
  int ijk[3];
  if (!NearestVoxel(this->Mask, this->Cursor, ijk) || !this->Mask->GetPointData()->GetScalars())
  {
    return false;
  }
  return this->Mask->GetScalarComponentAsDouble(ijk[0], ijk[1], ijk[2], 0) > 0.0;
}

int SliceViews::sliceIndex(int view) const
{
  if (!this->Volume)
  {
    return -1;
  }
  // The volume axis closest to the view's normal: the largest entry of the direction matrix's
  // row for the view's LPS axis.
  const int axis = SliceAxis(std::max(0, std::min(2, view)));
  vtkMatrix3x3* direction = this->Volume->GetDirectionMatrix();
  int along = 0;
  for (int c = 1; c < 3; ++c)
  {
    if (std::abs(direction->GetElement(axis, c)) > std::abs(direction->GetElement(axis, along)))
    {
      along = c;
    }
  }
  double continuous[3];
  this->Volume->TransformPhysicalPointToContinuousIndex(this->Cursor, continuous);
  const int* extent = this->Volume->GetExtent();
  const long index = std::lround(continuous[along]);
  return static_cast<int>(
    std::min<long>(extent[2 * along + 1], std::max<long>(extent[2 * along], index)));
}

QString SliceViews::cursorText() const
{
  if (!this->Volume)
  {
    return "Cursor: no volume";
  }
  static const char* const plus[3] = { "L", "P", "S" };
  static const char* const minus[3] = { "R", "A", "I" };
  QStringList parts;
  for (int axis = 0; axis < 3; ++axis)
  {
    parts << QString("%1 %2")
               .arg(this->Cursor[axis] >= 0 ? plus[axis] : minus[axis])
               .arg(std::abs(this->Cursor[axis]), 0, 'f', 1);
  }
  QString text = QString("Cursor %1 mm").arg(parts.join(", "));
  double value = 0.0;
  if (this->cursorValue(value))
  {
    text += QString(": %1").arg(value, 0, 'g', 5);
    if (this->cursorSegmented())
    {
      text += " (segmented)";
    }
  }
  return text;
}

vtkPolyData* SliceViews::crosshair(int view) const
{
  return this->Views[std::max(0, std::min(2, view))]->crosshairData;
}

void SliceViews::updateCrosshairs()
{
  if (this->CursorLabel)
  {
    this->CursorLabel->setText(this->cursorText());
  }
  if (!this->Volume)
  {
    return;
  }
  for (View* v : this->Views)
  {
    // In view v, the slice of view w is the line where w's axis is at the cursor, running
    // along the third axis over the box; drawn half a voxel in front of the slice.
    const int normal = SliceAxis(v->index);
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    vtkNew<vtkCellArray> lines;
    vtkNew<vtkUnsignedCharArray> colours;
    colours->SetName("Colors");
    colours->SetNumberOfComponents(3);
    for (int w = 0; w < 3; ++w)
    {
      if (w == v->index)
      {
        continue;
      }
      const int fixed = SliceAxis(w);
      const int running = 3 - normal - fixed;
      double a[3], b[3];
      for (int axis = 0; axis < 3; ++axis)
      {
        a[axis] = b[axis] = this->Cursor[axis] - 0.5 * this->StepLength * v->viewDirection[axis];
      }
      a[running] = this->Bounds[2 * running];
      b[running] = this->Bounds[2 * running + 1];
      const vtkIdType ids[2] = { points->InsertNextPoint(a), points->InsertNextPoint(b) };
      lines->InsertNextCell(2, ids);
      colours->InsertNextTypedTuple(SliceColours[w]);
    }
    v->crosshairData->SetPoints(points);
    v->crosshairData->SetLines(lines);
    v->crosshairData->GetCellData()->SetScalars(colours);
    v->crosshairData->Modified();
  }
}

QString SliceViews::positionText(int view) const
{
  const double position = this->slicePosition(view);
  const int axis = SliceAxis(view);
  double direction[3] = { 0, 0, 0 };
  direction[axis] = position >= 0 ? 1.0 : -1.0;
  return QString("%1 %2 mm").arg(PatientLetter(direction)).arg(std::abs(position), 0, 'f', 1);
}

QStringList SliceViews::edgeLetters(int view) const
{
  const View* v = this->Views[std::max(0, std::min(2, view))];
  const double* d = v->viewDirection;
  const double* u = v->viewUp;
  const double r[3] = {
    d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2], d[0] * u[1] - d[1] * u[0]
  };
  const double down[3] = { -u[0], -u[1], -u[2] };
  const double left[3] = { -r[0], -r[1], -r[2] };
  return { PatientLetter(u), PatientLetter(down), PatientLetter(left), PatientLetter(r) };
}

void SliceViews::updateAnnotation(int view)
{
  View* v = this->Views[view];
  if (!this->Volume)
  {
    return;
  }
  const QStringList letters = this->edgeLetters(view);
  v->annotation->SetText(vtkCornerAnnotation::UpperEdge, letters[0].toUtf8().constData());
  v->annotation->SetText(vtkCornerAnnotation::LowerEdge, letters[1].toUtf8().constData());
  v->annotation->SetText(vtkCornerAnnotation::LeftEdge, letters[2].toUtf8().constData());
  v->annotation->SetText(vtkCornerAnnotation::RightEdge, letters[3].toUtf8().constData());
  v->annotation->SetText(
    vtkCornerAnnotation::UpperLeft, this->positionText(view).toUtf8().constData());
}

void SliceViews::render()
{
  for (View* view : this->Views)
  {
    view->window->Render();
  }
}
