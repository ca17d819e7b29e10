#include "vtkBenderRibbonWidget.h"

#include "vtkBenderRibbonRepresentation.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkObjectFactory.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkWidgetCallbackMapper.h>
#include <vtkWidgetEvent.h>

vtkStandardNewMacro(vtkBenderRibbonWidget);

vtkBenderRibbonWidget::vtkBenderRibbonWidget()
{
  this->CallbackMapper->SetCallbackMethod(vtkCommand::LeftButtonPressEvent,
    vtkWidgetEvent::Select,
    this,
    vtkBenderRibbonWidget::SelectAction);
  this->CallbackMapper->SetCallbackMethod(
    vtkCommand::MouseMoveEvent, vtkWidgetEvent::Move, this, vtkBenderRibbonWidget::MoveAction);
  this->CallbackMapper->SetCallbackMethod(vtkCommand::LeftButtonReleaseEvent,
    vtkWidgetEvent::EndSelect,
    this,
    vtkBenderRibbonWidget::EndSelectAction);
}

void vtkBenderRibbonWidget::SetRepresentation(vtkBenderRibbonRepresentation* representation)
{
  this->Superclass::SetWidgetRepresentation(representation);
}

vtkBenderRibbonRepresentation* vtkBenderRibbonWidget::GetRibbonRepresentation()
{
  if (!this->WidgetRep)
  {
    this->CreateDefaultRepresentation();
  }
  return vtkBenderRibbonRepresentation::SafeDownCast(this->WidgetRep);
}

void vtkBenderRibbonWidget::CreateDefaultRepresentation()
{
  if (!this->WidgetRep)
  {
    this->WidgetRep = vtkBenderRibbonRepresentation::New();
  }
}

void vtkBenderRibbonWidget::SelectAction(vtkAbstractWidget* w)
{
  auto* self = static_cast<vtkBenderRibbonWidget*>(w);
  if (!self->Interactor || !self->WidgetRep)
  {
    return;
  }
  const int X = self->Interactor->GetEventPosition()[0];
  const int Y = self->Interactor->GetEventPosition()[1];
  if (self->WidgetRep->ComputeInteractionState(X, Y) == vtkBenderRibbonRepresentation::Outside)
  {
    return;
  }
  self->WidgetState = Active;
  self->GrabFocus(self->EventCallbackCommand);
  double position[2] = { static_cast<double>(X), static_cast<double>(Y) };
  self->WidgetRep->StartWidgetInteraction(position);
  self->EventCallbackCommand->SetAbortFlag(1);
  self->StartInteraction();
  self->InvokeEvent(vtkCommand::StartInteractionEvent, nullptr);
  self->Render();
}

void vtkBenderRibbonWidget::MoveAction(vtkAbstractWidget* w)
{
  auto* self = static_cast<vtkBenderRibbonWidget*>(w);
  if (!self->Interactor || !self->WidgetRep)
  {
    return;
  }
  const int X = self->Interactor->GetEventPosition()[0];
  const int Y = self->Interactor->GetEventPosition()[1];
  if (self->WidgetState != Active)
  {
    // Hover: highlight the handle under the cursor, render only when that changes.
    const int before = self->WidgetRep->GetInteractionState();
    const int now = self->WidgetRep->ComputeInteractionState(X, Y);
    if (now != before)
    {
      self->WidgetRep->BuildRepresentation();
      self->Render();
    }
    return;
  }
  double position[2] = { static_cast<double>(X), static_cast<double>(Y) };
  self->WidgetRep->WidgetInteraction(position);
  self->EventCallbackCommand->SetAbortFlag(1);
  self->InvokeEvent(vtkCommand::InteractionEvent, nullptr);
  self->Render();
}

void vtkBenderRibbonWidget::EndSelectAction(vtkAbstractWidget* w)
{
  auto* self = static_cast<vtkBenderRibbonWidget*>(w);
  if (self->WidgetState != Active || !self->WidgetRep)
  {
    return;
  }
  const int X = self->Interactor->GetEventPosition()[0];
  const int Y = self->Interactor->GetEventPosition()[1];
  double position[2] = { static_cast<double>(X), static_cast<double>(Y) };
  self->WidgetRep->EndWidgetInteraction(position);
  self->WidgetState = Start;
  self->ReleaseFocus();
  self->EventCallbackCommand->SetAbortFlag(1);
  self->EndInteraction();
  self->InvokeEvent(vtkCommand::EndInteractionEvent, nullptr);
  self->Render();
}

void vtkBenderRibbonWidget::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Dragging: " << (this->WidgetState == Active) << "\n";
}
