#include "HeadlessDemo.h"

#include "BenderSession.h"
#include "DemoPipeline.h"
#include "MeshIO.h"
#include "SegmentationErrors.h"
#include "WarpPlanIO.h"
#include "vtkBenderRibbonSource.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QProcess>
#include <QStandardPaths>
#include <QThread>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkWindowToImageFilter.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <memory>

namespace
{

// A private X server for off-screen rendering when the process has no display.
class PrivateDisplay
{
public:
  PrivateDisplay()
  {
    if (qEnvironmentVariableIsSet("DISPLAY") && !qEnvironmentVariable("DISPLAY").isEmpty())
    {
      this->Ready = true;
      return;
    }
    const QString xvfb = QStandardPaths::findExecutable("Xvfb");
    if (xvfb.isEmpty())
    {
      return;
    }
    for (int number = 91; number < 140 && !this->Ready; ++number)
    {
      if (QFileInfo::exists(QString("/tmp/.X%1-lock").arg(number)) ||
        QFileInfo::exists(QString("/tmp/.X11-unix/X%1").arg(number)))
      {
        continue;
      }
      this->Server = std::make_unique<QProcess>();
      this->Server->setProcessChannelMode(QProcess::ForwardedErrorChannel);
      this->Server->start(xvfb, { QString(":%1").arg(number), "-screen", "0", "1280x1024x24",
                                  "-nolisten", "tcp" });
      if (!this->Server->waitForStarted(5000))
      {
        continue;
      }
      for (int wait = 0; wait < 100; ++wait)
      {
        if (QFileInfo::exists(QString("/tmp/.X11-unix/X%1").arg(number)))
        {
          qputenv("DISPLAY", QString(":%1").arg(number).toLocal8Bit());
          this->Ready = true;
          break;
        }
        if (this->Server->state() != QProcess::Running)
        {
          break;
        }
        QThread::msleep(50);
      }
      if (!this->Ready)
      {
        this->Server->kill();
        this->Server->waitForFinished(2000);
        this->Server.reset();
      }
    }
  }
  ~PrivateDisplay()
  {
    if (this->Server)
    {
      this->Server->terminate();
      this->Server->waitForFinished(3000);
    }
  }
  bool Ready = false;

private:
  std::unique_ptr<QProcess> Server;
};

bool RenderScreenshot(
  vtkPolyData* surface, vtkPolyData* before, const bender::WarpPlan& plan, const std::string& path)
{
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.12, 0.13, 0.16);
  renderer->SetBackground2(0.32, 0.34, 0.40);
  renderer->GradientBackgroundOn();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(surface);
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.86, 0.36, 0.32);
  actor->GetProperty()->SetSpecular(0.3);
  actor->GetProperty()->SetOpacity(0.75);
  renderer->AddActor(actor);
  // The surface before the plan as a pale ghost, so that the bend shows.
  vtkNew<vtkPolyDataMapper> beforeMapper;
  beforeMapper->SetInputData(before);
  beforeMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> beforeActor;
  beforeActor->SetMapper(beforeMapper);
  beforeActor->GetProperty()->SetColor(0.8, 0.85, 0.95);
  beforeActor->GetProperty()->SetOpacity(0.22);
  renderer->AddActor(beforeActor);
  vtkNew<vtkBenderRibbonSource> ribbon;
  vtkNew<vtkPolyDataMapper> ribbonMapper;
  vtkNew<vtkActor> ribbonActor;
  if (!plan.warps.empty())
  {
    // The final ribbon of the last warp, where the surgeon's hands let go.
    ribbon->SetRibbon(plan.warps.back().final);
    ribbon->SetWidth(1.2);
    ribbonMapper->SetInputConnection(ribbon->GetOutputPort(0));
    ribbonActor->SetMapper(ribbonMapper);
    ribbonActor->GetProperty()->SetColor(1.0, 0.78, 0.2);
    renderer->AddActor(ribbonActor);
  }
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(1200, 900);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(30);
  renderer->GetActiveCamera()->Elevation(15);
  renderer->GetActiveCamera()->Zoom(1.5);
  renderer->ResetCameraClippingRange();
  window->Render();
  vtkNew<vtkWindowToImageFilter> image;
  image->SetInput(window);
  image->ReadFrontBufferOff();
  image->Update();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputConnection(image->GetOutputPort());
  writer->Write();
  return QFileInfo(QString::fromStdString(path)).size() > 0;
}

}

int RunHeadlessDemo(const QString& outDir, bool segment)
{
  if (!QDir().mkpath(outDir))
  {
    std::fprintf(stderr, "bender: cannot create the output folder %s\n", qPrintable(outDir));
    return 1;
  }
  const std::string out = QDir(outDir).absolutePath().toStdString();
  bender::BenderSession session;
  session.SetMessageCallback([](const bender::LogicMessage& m) {
    std::fprintf(m.severity == bender::MessageSeverity::Info ? stdout : stderr, "%s%s\n",
      m.severity == bender::MessageSeverity::Info ? "" : (m.severity == bender::MessageSeverity::Warning ? "warning: " : "error: "),
      m.text.c_str());
    std::fflush(stdout);
  });

  bool segmented = false;
  if (segment)
  {
    std::printf("Segmenting the demo vessel (MRA-like phantom of %s)...\n", bender::DemoVesselPath().c_str());
    std::fflush(stdout);
    bender::ProgressReporter progress;
    std::string lastStage;
    progress.onProgress = [&lastStage](const std::string& stage, double) {
      if (stage != lastStage)
      {
        lastStage = stage;
        std::printf("  %s\n", stage.c_str());
        std::fflush(stdout);
      }
    };
    try
    {
      bender::DemoVessel demo = bender::SegmentDemoVessel(bender::DemoVesselPath(), {}, progress);
      std::printf("%s\n", demo.summary.c_str());
      segmented = session.SetSurface(demo.surface, "demo vessel (segmented)");
      if (segmented)
      {
        bender::WriteMesh(demo.surface, out + "/demo-segmented.vtp");
      }
    }
    catch (const std::exception& e)
    {
      std::fprintf(stderr, "warning: segmentation failed (%s); using the vessel surface\n", e.what());
    }
  }
  if (!segmented && !session.LoadSurface(bender::DemoVesselPath()))
  {
    return 1;
  }
  if (!session.LoadPlan(bender::DemoPlanPath()))
  {
    return 1;
  }
  const bender::MeshCheckReport report = session.CheckSurface();
  const std::string reportText = bender::FormatReportText(report, "demo-bent.stl");
  {
    std::ofstream file(out + "/demo-check.txt");
    file << reportText;
  }
  std::printf("%s", reportText.c_str());
  if (!report.Clean())
  {
    std::fprintf(stderr, "warning: the check found problems (see demo-check.txt); exporting anyway\n");
  }
  bool ok = session.Export(out + "/demo-bent.stl");
  ok = session.Export(out + "/demo-bent.vtp") && ok;
  ok = session.SavePlan(out + "/demo-plan.bender.json") && ok;

  std::string screenshot = out + "/demo.png";
  PrivateDisplay display;
  if (display.Ready)
  {
    if (!RenderScreenshot(session.GetSurface(), session.GetOriginalSurface(), session.GetPlan(), screenshot))
    {
      std::fprintf(stderr, "warning: the screenshot could not be written\n");
      screenshot.clear();
    }
  }
  else
  {
    std::fprintf(stderr, "warning: no display and no Xvfb: screenshot skipped (install xvfb)\n");
    screenshot.clear();
  }

  std::printf("\nFiles written to %s:\n", out.c_str());
  for (const char* name : { "demo-segmented.vtp", "demo-bent.stl", "demo-bent.vtp", "demo-plan.bender.json",
         "demo-check.txt", "demo.png" })
  {
    if (QFileInfo::exists(QString::fromStdString(out + "/" + name)))
    {
      std::printf("  %s/%s\n", out.c_str(), name);
    }
  }
  std::printf("Frame LPS, unit mm. Check the export with: bender-cli check %s/demo-bent.stl\n", out.c_str());
  return ok ? 0 : 1;
}
