/**
 * @class   vtkBenderRibbonWidget
 * @brief   3D widget to hold and bend the ribbon of the Bender paper with the mouse
 *
 * Pairs with vtkBenderRibbonRepresentation. Left button on a handle starts a drag
 * (StartInteractionEvent), moving drags it (InteractionEvent, with the representation's ribbon
 * updated), releasing ends it (EndInteractionEvent). Hovering highlights the handle under the
 * cursor. Events away from the handles pass through to the camera.
 *
 * The widget does not warp anything: the application listens to InteractionEvent and hands
 * GetRibbon() to its logic (which refuses an invalid ribbon, see the representation).
 */

#ifndef vtkBenderRibbonWidget_h
#define vtkBenderRibbonWidget_h

#include "vtkAbstractWidget.h"
#include "vtkBenderWidgetsModule.h"

class vtkBenderRibbonRepresentation;

class VTKBENDERWIDGETS_EXPORT vtkBenderRibbonWidget : public vtkAbstractWidget
{
public:
  static vtkBenderRibbonWidget* New();
  vtkTypeMacro(vtkBenderRibbonWidget, vtkAbstractWidget);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** The representation (created on demand). */
  void SetRepresentation(vtkBenderRibbonRepresentation* representation);
  vtkBenderRibbonRepresentation* GetRibbonRepresentation();
  void CreateDefaultRepresentation() override;

  /** True while a handle is being dragged. */
  bool IsDragging() const { return this->WidgetState == Active; }

protected:
  vtkBenderRibbonWidget();
  ~vtkBenderRibbonWidget() override = default;

  enum
  {
    Start = 0,
    Active
  };
  int WidgetState = Start;

  static void SelectAction(vtkAbstractWidget* widget);
  static void MoveAction(vtkAbstractWidget* widget);
  static void EndSelectAction(vtkAbstractWidget* widget);

private:
  vtkBenderRibbonWidget(const vtkBenderRibbonWidget&) = delete;
  void operator=(const vtkBenderRibbonWidget&) = delete;
};

#endif
