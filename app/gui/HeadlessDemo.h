#ifndef HeadlessDemo_h
#define HeadlessDemo_h

#include <QString>

/// `bender --demo-headless`: runs bender::RunDemo (modules/Logic/RunDemo.h) into `outDir`,
/// printing its progress and the files written on stdout and problems on stderr. Returns the
/// process exit status: 0 done, 1 a step failed.
int RunHeadlessDemo(const QString& outDir, bool segment);

#endif
