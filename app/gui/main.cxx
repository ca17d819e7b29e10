// bender: the Bender application.
//   bender [FILE...]                 the window, opening meshes, volumes or plans
//   bender --demo                    the window on the built-in demo, ready to grab
//   bender --demo --headless [--out DIR]
//                                    the same job without a window: segment, apply the demo
//                                    plan, check, export and screenshot into DIR (default out)
#include "BendPanel.h"
#include "HeadlessDemo.h"
#include "MainWindow.h"

#include <QApplication>
#include <QCommandLineParser>
#include <QCoreApplication>
#include <QSurfaceFormat>
#include <QVTKOpenGLNativeWidget.h>

#include <vtkOutputWindow.h>

#include <cstdio>
#include <cstring>

int main(int argc, char** argv)
{
  bool headless = false;
  for (int i = 1; i < argc; ++i)
  {
    headless |= std::strcmp(argv[i], "--headless") == 0;
  }
  if (headless)
  {
    QCoreApplication application(argc, argv);
    QCoreApplication::setApplicationName("Bender");
    QCommandLineParser parser;
    parser.setApplicationDescription("Bender: ribbon-warp surgery planning (headless main job)");
    parser.addHelpOption();
    parser.addOption({ "demo", "Run the built-in demo." });
    parser.addOption({ "headless", "No window: run the job and write files." });
    parser.addOption({ "out", "Output folder (default: out).", "DIR", "out" });
    parser.addOption({ "no-segmentation", "Bend the vessel surface itself, skip the phantom." });
    parser.process(application);
    if (!parser.isSet("demo"))
    {
      std::fprintf(stderr, "bender: --headless runs the demo job; add --demo\n");
      return 2;
    }
    vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
    return RunHeadlessDemo(parser.value("out"), !parser.isSet("no-segmentation"));
  }

  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  QCoreApplication::setOrganizationName("Bender");
  QCoreApplication::setApplicationName("Bender");
  QCommandLineParser parser;
  parser.setApplicationDescription("Bender: ribbon-warp surgery planning");
  parser.addHelpOption();
  parser.addOption({ "demo", "Open on the built-in demo: segmented vessel, ribbon on a branch." });
  parser.addOption({ "headless", "No window (with --demo): run the job and write files." });
  parser.addOption({ "out", "Output folder of --headless (default: out).", "DIR", "out" });
  parser.addOption({ "max-narrowing",
    "Lumen guard: hold a bend that narrows a branch by more than PERCENT (default 5; 0: off).",
    "PERCENT",
    "5" });
  parser.addPositionalArgument("files", "Meshes, volumes or plans to open.", "[FILE...]");
  parser.process(application);
  bool percentOk = false;
  const double maxNarrowing = parser.value("max-narrowing").toDouble(&percentOk);
  if (!percentOk || maxNarrowing < 0.0 || maxNarrowing > 50.0)
  {
    std::fprintf(stderr,
      "bender: --max-narrowing %s: give a percentage from 0 (off) to 50\n",
      qPrintable(parser.value("max-narrowing")));
    return 2;
  }

  MainWindow window;
  window.bendPanel()->setMaxNarrowing(maxNarrowing);
  window.show();
  if (parser.isSet("demo"))
  {
    window.startDemo();
  }
  for (const QString& file : parser.positionalArguments())
  {
    window.waitUntilIdle(600000);
    window.openFile(file);
  }
  return application.exec();
}
