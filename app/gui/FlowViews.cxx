#include "FlowViews.h"

#include "CfdFlowResults.h"

#include <QCheckBox>
#include <QComboBox>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QVTKOpenGLNativeWidget.h>

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkLookupTable.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <limits>

namespace
{
const char* ArrayOf(FlowViews::Field field)
{
  return field == FlowViews::Field::Pressure ? bender::kPressureArrayName
                                             : bender::kWallShearStressMagnitudeArrayName;
}
} // namespace

FlowViews::FlowViews(QWidget* parent)
  : QWidget(parent)
{
  this->setObjectName("flowViews");
  auto* grid = new QGridLayout(this);
  grid->setContentsMargins(0, 0, 0, 0);
  this->FieldChoice = new QComboBox(this);
  this->FieldChoice->setObjectName("flowField");
  this->FieldChoice->addItem("Pressure (Pa)");
  this->FieldChoice->addItem("Wall shear stress (Pa)");
  this->FieldChoice->setToolTip(
    "Pressure relative to the outlets' mean, or the wall shear stress magnitude; both views "
    "share the colour scale");
  auto* row = new QHBoxLayout;
  row->addWidget(new QLabel("Colour by:", this));
  row->addWidget(this->FieldChoice);
  this->Streamlines = new QCheckBox("Streamlines", this);
  this->Streamlines->setObjectName("flowStreamlines");
  this->Streamlines->setToolTip(
    "The velocity traced from the inlet through each shape (the walls drawn translucent)");
  row->addWidget(this->Streamlines);
  row->addStretch(1);
  grid->addLayout(row, 0, 0, 1, 2);
  // Blue (low) to red (high), the same table in both views.
  this->Colours->SetHueRange(0.667, 0.0);
  this->Colours->SetNumberOfTableValues(256);
  this->Colours->Build();
  this->ScaleBar->SetLookupTable(this->Colours);
  this->ScaleBar->SetNumberOfLabels(5);
  this->ScaleBar->SetWidth(0.12);
  this->ScaleBar->SetHeight(0.7);
  this->ScaleBar->SetPosition(0.86, 0.15);
  this->ScaleBar->SetVerticalTitleSeparation(6);
  this->ScaleBar->UnconstrainedFontSizeOn();
  this->ScaleBar->GetTitleTextProperty()->SetFontSize(12);
  this->ScaleBar->GetLabelTextProperty()->SetFontSize(10);
  const char* titles[2] = { "Original", "Current shape" };
  const char* names[2] = { "flowViewOriginal", "flowViewCurrent" };
  for (int i = 0; i < 2; ++i)
  {
    View& v = this->Views[i];
    v.title = new QLabel(titles[i], this);
    v.title->setAlignment(Qt::AlignCenter);
    v.widget = new QVTKOpenGLNativeWidget(this);
    v.widget->setObjectName(names[i]);
    v.widget->setMinimumSize(240, 220);
    v.widget->setRenderWindow(v.window);
    v.window->SetMultiSamples(0);
    v.window->AddRenderer(v.renderer);
    v.renderer->SetBackground(0.12, 0.13, 0.16);
    v.renderer->SetBackground2(0.32, 0.34, 0.40);
    v.renderer->GradientBackgroundOn();
    v.mapper->SetLookupTable(this->Colours);
    v.mapper->UseLookupTableScalarRangeOn();
    v.mapper->SetScalarModeToUsePointFieldData();
    v.actor->SetMapper(v.mapper);
    v.actor->GetProperty()->SetSpecular(0.2);
    v.actor->VisibilityOff();
    v.renderer->AddActor(v.actor);
    v.lineMapper->ScalarVisibilityOff();
    v.lines->SetMapper(v.lineMapper);
    v.lines->GetProperty()->SetColor(0.95, 0.95, 0.85);
    v.lines->GetProperty()->SetLineWidth(1.5);
    v.lines->VisibilityOff();
    v.renderer->AddActor(v.lines);
    vtkNew<vtkInteractorStyleTrackballCamera> style;
    v.window->GetInteractor()->SetInteractorStyle(style);
    // The user moved this view's camera: the other follows.
    vtkNew<vtkCallbackCommand> moved;
    moved->SetClientData(this);
    moved->SetCallback(
      [](vtkObject* caller, unsigned long, void* self, void*)
      {
        auto* views = static_cast<FlowViews*>(self);
        const bool second = caller == views->Views[1].window->GetInteractor()->GetInteractorStyle();
        views->follow(second ? 1 : 0);
      });
    style->AddObserver(vtkCommand::InteractionEvent, moved);
    style->AddObserver(vtkCommand::EndInteractionEvent, moved);
    grid->addWidget(v.title, 1, i);
    grid->addWidget(v.widget, 2, i);
    grid->setColumnStretch(i, 1);
  }
  grid->setRowStretch(2, 1);
  this->Views[1].renderer->AddActor2D(this->ScaleBar);
  this->ScaleBar->VisibilityOff();
  connect(this->FieldChoice,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    [this]() { this->showField(); });
  connect(this->Streamlines,
    &QCheckBox::toggled,
    this,
    [this](bool on) { this->setStreamlinesShown(on); });
}

FlowViews::~FlowViews() = default;

void FlowViews::setSurfaces(vtkPolyData* original, vtkPolyData* current, vtkCamera* like)
{
  vtkPolyData* surfaces[2] = { original, current };
  for (int i = 0; i < 2; ++i)
  {
    View& v = this->Views[i];
    v.surface = surfaces[i];
    v.mapper->SetInputData(surfaces[i]);
    v.actor->SetVisibility(surfaces[i] != nullptr);
  }
  this->showField();
  // Both framed from the front (anterior: LPS -y towards the viewer, superior up), together.
  vtkRenderer* first = this->Views[0].renderer;
  vtkCamera* camera = first->GetActiveCamera();
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(0, -1, 0);
  camera->SetViewUp(0, 0, 1);
  if (like)
  {
    const double* d = like->GetDirectionOfProjection();
    camera->SetPosition(-d[0], -d[1], -d[2]);
    camera->SetViewUp(like->GetViewUp());
  }
  double bounds[6] = { 0, -1, 0, -1, 0, -1 };
  for (const View& v : this->Views)
  {
    if (v.surface && v.surface->GetNumberOfPoints() > 0)
    {
      double b[6];
      v.surface->GetBounds(b);
      for (int k = 0; k < 3; ++k)
      {
        bounds[2 * k] =
          bounds[2 * k] > bounds[2 * k + 1] ? b[2 * k] : std::min(bounds[2 * k], b[2 * k]);
        bounds[2 * k + 1] = std::max(bounds[2 * k + 1], b[2 * k + 1]);
      }
    }
  }
  if (bounds[0] <= bounds[1])
  {
    first->ResetCamera(bounds);
  }
  this->follow(0);
  this->render();
}

void FlowViews::setStreamlines(vtkPolyData* original, vtkPolyData* current)
{
  vtkPolyData* lines[2] = { original, current };
  for (int i = 0; i < 2; ++i)
  {
    this->Views[i].lineMapper->SetInputData(lines[i]);
  }
  this->Streamlines->setEnabled(original || current);
  this->setStreamlinesShown(this->Streamlines->isChecked());
}

void FlowViews::setTitles(const QString& left, const QString& right)
{
  this->Views[0].title->setText(left);
  this->Views[1].title->setText(right);
}

void FlowViews::setStreamlinesShown(bool shown)
{
  if (this->Streamlines->isChecked() != shown)
  {
    this->Streamlines->setChecked(shown); // toggled() comes back here
    return;
  }
  for (View& v : this->Views)
  {
    const bool has = shown && v.lineMapper->GetInput() != nullptr;
    v.lines->SetVisibility(has);
    v.actor->GetProperty()->SetOpacity(has ? 0.35 : 1.0);
  }
  this->render();
}

bool FlowViews::streamlinesShown() const
{
  return this->Streamlines->isChecked();
}

void FlowViews::setField(Field field)
{
  this->FieldChoice->setCurrentIndex(field == Field::Pressure ? 0 : 1);
  this->showField();
}

FlowViews::Field FlowViews::field() const
{
  return this->FieldChoice->currentIndex() == 0 ? Field::Pressure : Field::WallShearStress;
}

void FlowViews::range(double range[2]) const
{
  const double* r = this->Colours->GetRange();
  range[0] = r[0];
  range[1] = r[1];
}

QString FlowViews::scaleTitle() const
{
  return QString::fromUtf8(this->ScaleBar->GetTitle() ? this->ScaleBar->GetTitle() : "");
}

void FlowViews::showField()
{
  const Field field = this->field();
  const char* name = ArrayOf(field);
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (View& v : this->Views)
  {
    v.mapper->SelectColorArray(name);
    vtkDataArray* values = v.surface ? v.surface->GetPointData()->GetArray(name) : nullptr;
    v.mapper->SetScalarVisibility(values != nullptr);
    if (values)
    {
      double r[2];
      values->GetRange(r);
      low = std::min(low, r[0]);
      high = std::max(high, r[1]);
    }
  }
  if (!(low <= high))
  {
    low = 0.0;
    high = 1.0;
  }
  if (field == Field::WallShearStress)
  {
    low = 0.0; // a magnitude: the scale starts at no stress
  }
  this->Colours->SetTableRange(low, high > low ? high : low + 1.0);
  this->ScaleBar->SetTitle(field == Field::Pressure ? "Pressure (Pa)" : "WSS (Pa)");
  this->ScaleBar->SetVisibility(this->Views[0].surface || this->Views[1].surface);
  this->render();
}

void FlowViews::follow(int from)
{
  if (this->Following)
  {
    return;
  }
  this->Following = true;
  vtkCamera* source = this->Views[from].renderer->GetActiveCamera();
  View& other = this->Views[1 - from];
  vtkCamera* target = other.renderer->GetActiveCamera();
  target->SetFocalPoint(source->GetFocalPoint());
  target->SetPosition(source->GetPosition());
  target->SetViewUp(source->GetViewUp());
  target->SetViewAngle(source->GetViewAngle());
  target->SetParallelScale(source->GetParallelScale());
  this->Views[from].renderer->ResetCameraClippingRange();
  other.renderer->ResetCameraClippingRange();
  other.window->Render();
  this->Following = false;
}

QVTKOpenGLNativeWidget* FlowViews::view(int which) const
{
  return this->Views[which == 0 ? 0 : 1].widget;
}

vtkRenderer* FlowViews::renderer(int which) const
{
  return this->Views[which == 0 ? 0 : 1].renderer;
}

vtkPolyDataMapper* FlowViews::mapper(int which) const
{
  return this->Views[which == 0 ? 0 : 1].mapper;
}

void FlowViews::render()
{
  for (View& v : this->Views)
  {
    v.window->Render();
  }
}
