#ifndef HeadlessDemo_h
#define HeadlessDemo_h

#include <QString>

/// The main job without a window: segment the demo vessel (the MRA-like phantom; the vessel
/// surface itself when segmentation is unavailable), apply the demo plan, check, export (STL
/// with the frame and unit in its header, VTP, the plan) and render a screenshot off screen,
/// all into `outDir`. Progress and the list of files go to stdout, problems to stderr.
/// Rendering needs an X display: without DISPLAY a private Xvfb is started when installed,
/// otherwise the screenshot is skipped with a message. Returns the process exit status:
/// 0 done, 1 a step failed.
int RunHeadlessDemo(const QString& outDir, bool segment);

#endif
