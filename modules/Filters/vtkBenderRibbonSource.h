/**
 * @class   vtkBenderRibbonSource
 * @brief   polydata of a ribbon for display: the twisted strip, the wire, the RoI tube
 *
 * Output port 0: the ribbon strip, a triangle strip of half-width Width on both sides of the
 * wire along N_s (so the twist is visible), with point normals B_s and a "s" point array.
 * Output port 1: the wire, one polyline with Resolution + 1 points and a "s" array.
 * Output port 2: the region of influence, the boundary of {P : dist(P, wire) < Radius}: a tube
 * swept along the wire closed by hemispheres at the free ends (empty when Radius <= 0).
 *
 * Coordinates are those of the model (LPS mm for segmented vessels). An invalid ribbon (spec
 * convention 11) produces empty outputs, GetValid() false and GetLastError() with the reason;
 * that is not a pipeline error, so that a widget can show the invalid state.
 */

#ifndef vtkBenderRibbonSource_h
#define vtkBenderRibbonSource_h

#include "vtkBenderFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include "WarpPlan.h"

#include <string>

class VTKBENDERFILTERS_EXPORT vtkBenderRibbonSource : public vtkPolyDataAlgorithm
{
public:
  static vtkBenderRibbonSource* New();
  vtkTypeMacro(vtkBenderRibbonSource, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** The ribbon's two end frames and extra turns. */
  void SetRibbon(const bender::RibbonSpec& ribbon);
  const bender::RibbonSpec& GetRibbon() const { return this->Ribbon; }

  ///@{
  /** Samples along the wire, [2, 4096], default 128. */
  vtkSetClampMacro(Resolution, int, 2, 4096);
  vtkGetMacro(Resolution, int);
  ///@}

  ///@{
  /** Half-width of the strip in model units, >= 0, default 1. */
  vtkSetClampMacro(Width, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Width, double);
  ///@}

  ///@{
  /** Radius of the region-of-influence tube, >= 0 (0: no tube), default 0. */
  vtkSetClampMacro(Radius, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Radius, double);
  ///@}

  ///@{
  /** Sides of the tube's cross-section, [3, 256], default 24. */
  vtkSetClampMacro(TubeSides, int, 3, 256);
  vtkGetMacro(TubeSides, int);
  ///@}

  /** Whether the last update saw a valid ribbon, and why not. */
  bool GetValid() const { return this->Valid; }
  const std::string& GetLastError() const { return this->LastError; }

protected:
  vtkBenderRibbonSource();
  ~vtkBenderRibbonSource() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Resolution = 128;
  double Width = 1.0;
  double Radius = 0.0;
  int TubeSides = 24;

private:
  vtkBenderRibbonSource(const vtkBenderRibbonSource&) = delete;
  void operator=(const vtkBenderRibbonSource&) = delete;

  bender::RibbonSpec Ribbon;
  bool Valid = true;
  std::string LastError;
};

#endif
