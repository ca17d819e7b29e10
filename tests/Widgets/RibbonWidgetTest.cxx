// The ribbon widget driven through its API and through a recorded event log
// (vtkInteractorEventRecorder), as VTK's own widget tests do. Needs a display (Xvfb).
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonSource.h"
#include "vtkBenderRibbonWidget.h"

#include "OutlineCrossings.h"
#include "Vec3.h"

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkImageData.h>
#include <vtkInteractorEventRecorder.h>
#include <vtkInteractorObserver.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataSilhouette.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkStripper.h>
#include <vtkWindowToImageFilter.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <sstream>
#include <vector>

using Rep = vtkBenderRibbonRepresentation;

namespace
{

struct Scene
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkRenderWindowInteractor> interactor;
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  vtkNew<vtkBenderRibbonWidget> widget;
  vtkNew<Rep> representation;

  Scene()
  {
    this->window->SetSize(400, 400);
    this->window->AddRenderer(this->renderer);
    this->interactor->SetRenderWindow(this->window);
    this->interactor->SetInteractorStyle(this->style);
    double bounds[6] = { -10, 10, -4, 4, -4, 4 };
    this->representation->PlaceWidget(bounds);
    this->representation->SetRadius(3);
    this->widget->SetInteractor(this->interactor);
    this->widget->SetRepresentation(this->representation);
    this->widget->On();
    this->renderer->GetActiveCamera()->SetPosition(0, 0, 60);
    this->renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
    this->renderer->GetActiveCamera()->SetViewUp(0, 1, 0);
    this->renderer->ResetCameraClippingRange();
    this->interactor->Initialize();
    this->window->Render();
  }

  void Display(int handle, double display[3])
  {
    double world[3];
    this->representation->GetHandlePosition(handle, world);
    vtkInteractorObserver::ComputeWorldToDisplay(
      this->renderer, world[0], world[1], world[2], display);
  }
};

struct EventCounter
{
  int start = 0, interaction = 0, end = 0;
};

void Count(vtkObject*, unsigned long event, void* clientData, void*)
{
  auto* counter = static_cast<EventCounter*>(clientData);
  if (event == vtkCommand::StartInteractionEvent)
    ++counter->start;
  else if (event == vtkCommand::InteractionEvent)
    ++counter->interaction;
  else if (event == vtkCommand::EndInteractionEvent)
    ++counter->end;
}

}

TEST(RibbonRepresentation, PlaceWidgetGivesAValidStraightRibbonWithATube)
{
  vtkNew<Rep> rep;
  double bounds[6] = { 0, 40, -5, 5, -5, 5 };
  rep->PlaceWidget(bounds);
  rep->SetRadius(4);
  const auto& ribbon = rep->GetRibbon();
  EXPECT_NEAR(ribbon.start.position.x, 10, 1e-12);
  EXPECT_NEAR(ribbon.end.position.x, 30, 1e-12);
  EXPECT_TRUE(rep->GetValid());
  EXPECT_GT(rep->GetRibbonSource()->GetOutput(0)->GetNumberOfPoints(), 0);
  // The region's tube is made only while it is drawn (opacity > 0); its outline always is, and
  // the bounds hold the region either way.
  rep->GetRibbonSource()->Update();
  EXPECT_EQ(rep->GetRibbonSource()->GetOutput(2)->GetNumberOfPoints(), 0);
  double* b = rep->GetBounds();
  EXPECT_LE(b[0], 10 - 4 + 1e-6);
  EXPECT_GE(b[1], 30 + 4 - 1e-6);
  rep->SetRegionOpacity(0.2);
  rep->GetRibbonSource()->Update();
  EXPECT_GT(rep->GetRibbonSource()->GetOutput(2)->GetNumberOfPoints(), 0);
  b = rep->GetBounds();
  EXPECT_LE(b[0], 10 - 4 + 1e-6);
  EXPECT_GE(b[1], 30 + 4 - 1e-6);
}

TEST(RibbonRepresentation, HandlesMovePositionTangentAndTwist)
{
  vtkNew<Rep> rep;
  double bounds[6] = { 0, 40, -5, 5, -5, 5 };
  rep->PlaceWidget(bounds);
  const double l = rep->GetHandleLength();

  const double end[3] = { 25, 8, 0 };
  ASSERT_TRUE(rep->MoveHandle(Rep::EndPosition, end));
  EXPECT_EQ(rep->GetRibbon().end.position.y, 8);
  // The tangent handle travels with its end.
  double tip[3];
  rep->GetHandlePosition(Rep::EndTangent, tip);
  EXPECT_NEAR(tip[0], 25 + l, 1e-12);
  EXPECT_NEAR(tip[1], 8, 1e-12);

  // Tangent handle straight "up" from the end: the end tangent becomes +y.
  const double up[3] = { 25, 8 + 5, 0 };
  ASSERT_TRUE(rep->MoveHandle(Rep::EndTangent, up));
  EXPECT_NEAR(rep->GetRibbon().end.tangent.y, 1.0, 1e-12);
  const auto n = rep->GetRibbon().end.normal;
  EXPECT_NEAR(n.x * 0 + n.y * 1 + n.z * 0, 0.0, 1e-12);

  // The start tangent handle is behind the start: moving it to -y makes the tangent +y.
  const auto s = rep->GetRibbon().start.position;
  const double behind[3] = { s.x, s.y - 3, s.z };
  ASSERT_TRUE(rep->MoveHandle(Rep::StartTangent, behind));
  EXPECT_NEAR(rep->GetRibbon().start.tangent.y, 1.0, 1e-12);

  // Normal handle: the twist; the normal stays orthogonal to the tangent.
  const double side[3] = { s.x + 2, s.y + 1, s.z + 0 };
  ASSERT_TRUE(rep->MoveHandle(Rep::StartNormal, side));
  const auto n0 = rep->GetRibbon().start.normal;
  const auto t0 = rep->GetRibbon().start.tangent;
  EXPECT_NEAR(n0.x * t0.x + n0.y * t0.y + n0.z * t0.z, 0.0, 1e-12);
  EXPECT_NEAR(n0.x, 1.0, 1e-12);

  // Degenerate moves are refused and change nothing.
  const double onEnd[3] = { 25, 8, 0 };
  EXPECT_FALSE(rep->MoveHandle(Rep::EndTangent, onEnd));
  const double nan[3] = { std::nan(""), 0, 0 };
  EXPECT_FALSE(rep->MoveHandle(Rep::EndPosition, nan));
  EXPECT_FALSE(rep->MoveHandle(Rep::Outside, end));
}

TEST(RibbonRepresentation, InvalidRibbonIsShownAsSuch)
{
  vtkNew<Rep> rep;
  double bounds[6] = { 0, 40, -5, 5, -5, 5 };
  rep->PlaceWidget(bounds);
  rep->SetRadius(3);
  rep->SetRegionOpacity(0.2);
  EXPECT_TRUE(rep->HasTranslucentPolygonalGeometry());
  const auto start = rep->GetRibbon().start.position;
  const double onStart[3] = { start.x, start.y, start.z };
  ASSERT_TRUE(rep->MoveHandle(Rep::EndPosition, onStart));
  EXPECT_FALSE(rep->GetValid());
  EXPECT_FALSE(rep->GetLastError().empty());
  EXPECT_EQ(rep->GetRibbonSource()->GetOutput(0)->GetNumberOfPoints(), 0);
  rep->SetRegionOpacity(0.2);
  EXPECT_FALSE(rep->HasTranslucentPolygonalGeometry());
  // Moving it away makes it valid again.
  const double away[3] = { start.x + 10, start.y, start.z };
  ASSERT_TRUE(rep->MoveHandle(Rep::EndPosition, away));
  EXPECT_TRUE(rep->GetValid());
}

TEST(RibbonWidget, RecordedEventLogDragsTheEndHandle)
{
  Scene scene;
  EventCounter counter;
  vtkNew<vtkCallbackCommand> observer;
  observer->SetCallback(Count);
  observer->SetClientData(&counter);
  scene.widget->AddObserver(vtkCommand::StartInteractionEvent, observer);
  scene.widget->AddObserver(vtkCommand::InteractionEvent, observer);
  scene.widget->AddObserver(vtkCommand::EndInteractionEvent, observer);

  const auto before = scene.representation->GetRibbon();
  double display[3];
  scene.Display(Rep::EndPosition, display);
  const int x = static_cast<int>(std::lround(display[0]));
  const int y = static_cast<int>(std::lround(display[1]));
  std::ostringstream log;
  log << "# StreamVersion 1.2\n";
  log << "MouseMoveEvent " << x << " " << y << " 0 0 0 0 0\n";
  log << "LeftButtonPressEvent " << x << " " << y << " 0 0 0 0 0\n";
  for (int step = 1; step <= 10; ++step)
  {
    log << "MouseMoveEvent " << x << " " << y + 6 * step << " 0 0 0 0 0\n";
  }
  log << "LeftButtonReleaseEvent " << x << " " << y + 60 << " 0 0 0 0 0\n";

  vtkNew<vtkInteractorEventRecorder> recorder;
  recorder->SetInteractor(scene.interactor);
  recorder->ReadFromInputStringOn();
  recorder->SetInputString(log.str().c_str());
  recorder->Play();
  recorder->Off();

  EXPECT_EQ(counter.start, 1);
  EXPECT_EQ(counter.interaction, 10);
  EXPECT_EQ(counter.end, 1);
  EXPECT_FALSE(scene.widget->IsDragging());
  const auto after = scene.representation->GetRibbon();
  // Dragged up the screen (+y in this camera) by 60 pixels; x and z stay; the start stays.
  EXPECT_GT(after.end.position.y - before.end.position.y, 1.0);
  EXPECT_NEAR(after.end.position.x, before.end.position.x, 1e-6);
  EXPECT_NEAR(after.end.position.z, before.end.position.z, 1e-6);
  EXPECT_EQ(after.start.position.x, before.start.position.x);
  EXPECT_EQ(after.start.position.y, before.start.position.y);
  // The handle follows the cursor: 60 pixels at the handle's depth.
  double now[3];
  scene.Display(Rep::EndPosition, now);
  EXPECT_NEAR(now[1], y + 60, 1.0);
}

TEST(RibbonWidget, PressAwayFromHandlesDoesNotStartADrag)
{
  Scene scene;
  EventCounter counter;
  vtkNew<vtkCallbackCommand> observer;
  observer->SetCallback(Count);
  observer->SetClientData(&counter);
  scene.widget->AddObserver(vtkCommand::StartInteractionEvent, observer);
  const auto before = scene.representation->GetRibbon();
  vtkNew<vtkInteractorEventRecorder> recorder;
  recorder->SetInteractor(scene.interactor);
  recorder->ReadFromInputStringOn();
  recorder->SetInputString("# StreamVersion 1.2\n"
                           "LeftButtonPressEvent 5 5 0 0 0 0 0\n"
                           "MouseMoveEvent 30 30 0 0 0 0 0\n"
                           "LeftButtonReleaseEvent 30 30 0 0 0 0 0\n");
  recorder->Play();
  recorder->Off();
  EXPECT_EQ(counter.start, 0);
  EXPECT_EQ(scene.representation->GetRibbon().end.position.y, before.end.position.y);
}

TEST(RibbonWidget, DrawsTheRibbonAndItsRegion)
{
  Scene scene;
  const double bent[3] = { 6, 6, 0 };
  ASSERT_TRUE(scene.representation->MoveHandle(Rep::EndPosition, bent));
  // Normals along the view: the strip faces the camera.
  auto ribbon = scene.representation->GetRibbon();
  ribbon.start.normal = ribbon.end.normal = { 0, 0, 1 };
  ribbon.end.tangent = { 1, 0, 0 };
  ribbon.start.normal = { 0, 1, 0 };
  ribbon.end.normal = { 0, 1, 0 };
  scene.representation->SetRibbon(ribbon);
  scene.representation->SetStripWidth(1.0);
  scene.window->Render();
  vtkNew<vtkWindowToImageFilter> image;
  image->SetInput(scene.window);
  image->ReadFrontBufferOff();
  image->Update();
  // The gold strip and the blue outline of the region are drawn.
  vtkImageData* pixels = image->GetOutput();
  int dims[3];
  pixels->GetDimensions(dims);
  const auto* rgb = static_cast<unsigned char*>(pixels->GetScalarPointer());
  const int components = pixels->GetNumberOfScalarComponents();
  int gold = 0, blue = 0;
  for (int i = 0; i < dims[0] * dims[1]; ++i)
  {
    const int r = rgb[components * i], g = rgb[components * i + 1], b = rgb[components * i + 2];
    gold += (r > 120 && g > 80 && b < 90) ? 1 : 0;
    blue += (b > 150 && r < 160) ? 1 : 0;
  }
  EXPECT_GT(gold, 300);
  EXPECT_GT(blue, 300);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(BENDER_ARTIFACT_DIR "/ribbon-widget.png");
  writer->SetInputConnection(image->GetOutputPort());
  writer->Write();
}

TEST(RibbonRepresentation, HandlesSayWhatTheyAreByShapeAndColour)
{
  vtkNew<Rep> rep;
  double bounds[6] = { 0, 40, -5, 5, -5, 5 };
  rep->PlaceWidget(bounds);
  auto colour = [&](int handle)
  {
    double c[3];
    rep->GetHandleActor(handle)->GetProperty()->GetColor(c);
    return std::array<double, 3>{ c[0], c[1], c[2] };
  };
  auto shapePoints = [&](int handle)
  {
    auto* mapper = rep->GetHandleActor(handle)->GetMapper();
    mapper->Update();
    return mapper->GetInput()->GetNumberOfPoints();
  };
  EXPECT_EQ(rep->GetHandleActor(Rep::Outside), nullptr);
  // The two handles of a role look alike; the three roles differ in colour and shape.
  EXPECT_EQ(colour(Rep::StartPosition), colour(Rep::EndPosition));
  EXPECT_EQ(colour(Rep::StartTangent), colour(Rep::EndTangent));
  EXPECT_EQ(colour(Rep::StartNormal), colour(Rep::EndNormal));
  EXPECT_NE(colour(Rep::StartPosition), colour(Rep::StartTangent));
  EXPECT_NE(colour(Rep::StartPosition), colour(Rep::StartNormal));
  EXPECT_NE(colour(Rep::StartTangent), colour(Rep::StartNormal));
  EXPECT_NE(shapePoints(Rep::StartPosition), shapePoints(Rep::StartTangent));
  EXPECT_NE(shapePoints(Rep::StartPosition), shapePoints(Rep::StartNormal));
  EXPECT_NE(shapePoints(Rep::StartTangent), shapePoints(Rep::StartNormal));
  EXPECT_STREQ(Rep::GetHandleRole(Rep::EndPosition), "end");
  EXPECT_STREQ(Rep::GetHandleRole(Rep::EndTangent), "tangent");
  EXPECT_STREQ(Rep::GetHandleRole(Rep::EndNormal), "twist");
  EXPECT_STREQ(Rep::GetHandleRole(Rep::Outside), "");
  // The tangent cones point away from the ribbon along the tangent (here +x at the end).
  auto* cone = rep->GetHandleActor(Rep::EndTangent)->GetMapper();
  cone->Update();
  double coneBounds[6];
  cone->GetInput()->GetBounds(coneBounds);
  EXPECT_GT(coneBounds[1] - coneBounds[0], coneBounds[3] - coneBounds[2]);
  // An invalid ribbon turns every handle red.
  const auto start = rep->GetRibbon().start.position;
  const double onStart[3] = { start.x, start.y, start.z };
  ASSERT_TRUE(rep->MoveHandle(Rep::EndPosition, onStart));
  EXPECT_EQ(colour(Rep::StartTangent), colour(Rep::EndNormal));
  EXPECT_GT(colour(Rep::StartTangent)[0], 0.9);
  EXPECT_LT(colour(Rep::StartTangent)[1], 0.3);
}

TEST(RibbonWidget, HoverShowsWhatTheHandleDoes)
{
  Scene scene;
  const int handles[3] = { Rep::EndPosition, Rep::EndTangent, Rep::StartNormal };
  const char* hints[3] = { "end: drag to move", "tangent: drag to bend", "twist: drag to twist" };
  for (int i = 0; i < 3; ++i)
  {
    double display[3];
    scene.Display(handles[i], display);
    std::ostringstream log;
    log << "# StreamVersion 1.2\n"
        << "MouseMoveEvent " << std::lround(display[0]) << " " << std::lround(display[1])
        << " 0 0 0 0 0\n";
    vtkNew<vtkInteractorEventRecorder> recorder;
    recorder->SetInteractor(scene.interactor);
    recorder->ReadFromInputStringOn();
    recorder->SetInputString(log.str().c_str());
    recorder->Play();
    recorder->Off();
    EXPECT_EQ(scene.representation->GetInteractionState(), handles[i]);
    EXPECT_STREQ(scene.representation->GetHoverText(), hints[i]);
    // The handle under the cursor is highlighted.
    double c[3];
    scene.representation->GetHandleActor(handles[i])->GetProperty()->GetColor(c);
    EXPECT_GT(c[0], 0.9);
    EXPECT_GT(c[1], 0.9);
  }
  // The hint is drawn: light pixels right of and above the handle, none before the hover.
  scene.window->Render();
  vtkNew<vtkWindowToImageFilter> image;
  image->SetInput(scene.window);
  image->ReadFrontBufferOff();
  image->Update();
  vtkImageData* pixels = image->GetOutput();
  double display[3];
  scene.Display(Rep::StartNormal, display);
  int light = 0;
  for (int y = static_cast<int>(display[1]) + 10; y < static_cast<int>(display[1]) + 34; ++y)
    for (int x = static_cast<int>(display[0]) + 16; x < static_cast<int>(display[0]) + 150; ++x)
    {
      if (x < 0 || y < 0 || x >= 400 || y >= 400)
        continue;
      const auto* p = static_cast<unsigned char*>(pixels->GetScalarPointer(x, y, 0));
      light += (p[0] > 200 && p[1] > 200 && p[2] > 120) ? 1 : 0;
    }
  EXPECT_GT(light, 30);
  // Away from the handles: no hint.
  vtkNew<vtkInteractorEventRecorder> recorder;
  recorder->SetInteractor(scene.interactor);
  recorder->ReadFromInputStringOn();
  recorder->SetInputString("# StreamVersion 1.2\nMouseMoveEvent 3 3 0 0 0 0 0\n");
  recorder->Play();
  recorder->Off();
  EXPECT_STREQ(scene.representation->GetHoverText(), "");
}

// Issue 22: the region's outline while dragging is one simple closed curve, however tightly the
// ribbon is bent and wherever the camera looks from. The silhouette of the region's tube, drawn
// before, is a tangle of loops there (the swept tube folds where the wire bends tighter than R).
TEST(RibbonRepresentation, TheRegionOutlineIsASimpleClosedCurveAfterADrag)
{
  Scene scene;
  scene.representation->SetRadius(8);
  const bender::RibbonSpec straight = scene.representation->GetRibbon();
  int tubeCrossings = 0;
  for (const double angle : { 0.0, 60.0, 120.0, 160.0 })
  {
    // The end frame swung about +z by `angle` around the start, as dragging the end handle
    // round does.
    const double a = angle * 3.14159265358979 / 180.0;
    const bender::Vec3 axis{ 0, 0, 1 };
    bender::RibbonSpec ribbon = straight;
    ribbon.end.position = straight.start.position +
      bender::Rotate(axis, a, straight.end.position - straight.start.position);
    ribbon.end.tangent = bender::Rotate(axis, a, straight.end.tangent);
    ribbon.end.normal = bender::Rotate(axis, a, straight.end.normal);
    scene.representation->SetRibbon(ribbon);
    ASSERT_TRUE(scene.representation->GetValid()) << scene.representation->GetLastError();
    for (const std::array<double, 3>& eye :
      { std::array<double, 3>{ 0, 0, 60 }, { 40, 10, 40 }, { 0, 60, 5 } })
    {
      scene.renderer->GetActiveCamera()->SetPosition(eye.data());
      scene.renderer->ResetCameraClippingRange();
      scene.window->Render();
      const auto loops =
        bendertest::DisplayLoops(scene.representation->GetRegionOutline(), scene.renderer);
      EXPECT_TRUE(bendertest::IsSimpleClosedCurve(loops))
        << angle << " degrees, seen from " << eye[0] << " " << eye[1] << " " << eye[2] << ": "
        << loops.size() << " loops, " << bendertest::Crossings(loops) << " crossings";

      // The tube's silhouette for the same view: the case is one that tangles it.
      vtkNew<vtkBenderRibbonSource> tube;
      tube->SetRibbon(ribbon);
      tube->SetResolution(48);
      tube->SetTubeSides(32);
      tube->SetRadius(8);
      vtkNew<vtkPolyDataSilhouette> silhouette;
      silhouette->SetInputConnection(tube->GetOutputPort(2));
      silhouette->SetDirectionToCameraOrigin();
      silhouette->BorderEdgesOff();
      silhouette->SetCamera(scene.renderer->GetActiveCamera());
      vtkNew<vtkStripper> strips;
      strips->SetInputConnection(silhouette->GetOutputPort());
      strips->Update();
      tubeCrossings +=
        bendertest::Crossings(bendertest::DisplayLoops(strips->GetOutput(), scene.renderer));
    }
  }
  EXPECT_GT(tubeCrossings, 0);
  vtkNew<vtkWindowToImageFilter> image;
  image->SetInput(scene.window);
  image->ReadFrontBufferOff();
  image->Update();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(BENDER_ARTIFACT_DIR "/ribbon-region-outline.png");
  writer->SetInputConnection(image->GetOutputPort());
  writer->Write();
}
