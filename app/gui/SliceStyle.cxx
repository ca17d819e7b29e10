#include "SliceStyle.h"

#include <vtkCallbackCommand.h>
#include <vtkObjectFactory.h>
#include <vtkRenderWindowInteractor.h>

vtkStandardNewMacro(SliceStyle);

void SliceStyle::OnLeftButtonDown()
{
  vtkRenderWindowInteractor* rwi = this->Interactor;
  if (rwi->GetShiftKey() && !rwi->GetControlKey())
  {
    // The image style's window/level is its left drag without modifiers.
    rwi->SetShiftKey(0);
    this->Superclass::OnLeftButtonDown();
    rwi->SetShiftKey(1);
    return;
  }
  const int* at = rwi->GetEventPosition();
  this->FindPokedRenderer(at[0], at[1]);
  if (!this->CurrentRenderer)
  {
    return;
  }
  this->Dragging = true;
  this->GrabFocus(this->EventCallbackCommand);
  if (this->MoveCursor)
  {
    this->MoveCursor(at[0], at[1]);
  }
}

void SliceStyle::OnMouseMove()
{
  if (!this->Dragging)
  {
    this->Superclass::OnMouseMove();
    return;
  }
  const int* at = this->Interactor->GetEventPosition();
  if (this->MoveCursor)
  {
    this->MoveCursor(at[0], at[1]);
  }
}

void SliceStyle::OnLeftButtonUp()
{
  if (this->Dragging)
  {
    this->Dragging = false;
    this->ReleaseFocus();
    return;
  }
  this->Superclass::OnLeftButtonUp();
}
