#include "HeadlessDemo.h"

#include "BenderErrors.h"
#include "HeadlessDisplay.h"
#include "RunDemo.h"

#include <QDir>

#include <cstdio>
#include <exception>
#include <string>

int RunHeadlessDemo(const QString& outDir, bool segment)
{
  bender::RunDemoOptions options;
  options.outputDirectory = QDir(outDir).absolutePath().toStdString();
  options.segment = segment;
  std::string lastStage;
  options.progress.onProgress = [&lastStage](const std::string& stage, double)
  {
    if (stage != lastStage)
    {
      lastStage = stage;
      std::printf("  %s\n", stage.c_str());
      std::fflush(stdout);
    }
  };
  options.onMessage = [](const std::string& line, bool warning)
  {
    std::fprintf(warning ? stderr : stdout, "%s\n", line.c_str());
    std::fflush(warning ? stderr : stdout);
  };
  // demo.png needs a display: a private Xvfb without one (else RunDemo skips it, warning).
  bender::EnsureHeadlessDisplay();
  bender::RunDemoResult result;
  try
  {
    result = bender::RunDemo(options);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  std::printf("\nFiles written to %s:\n", options.outputDirectory.c_str());
  for (const std::string& file : result.written)
  {
    std::printf("  %s\n", file.c_str());
  }
  std::printf("Frame LPS, unit mm. Check the export with: bender-cli check %s/demo-bent.stl\n",
    options.outputDirectory.c_str());
  return 0;
}
