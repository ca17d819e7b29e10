#ifndef bender_FaultInjection_h
#define bender_FaultInjection_h

// A test hook for crash safety. With the environment variable BENDER_FAULT_AT=<point> (or
// <point>:<n>), the process kills itself with SIGKILL, as a crash or a power cut would (no
// destructor, no atexit handler, no flush of stdio buffers), the first (n-th) time it reaches
// FaultPoint("<point>"). Compiled into every build and inert unless the variable is set: a
// FaultPoint then costs one getenv. The crash-safety tests (tests/crash/CrashSafetyTest.cxx)
// run each operation under its points and check what the next process finds.
//
// The points (one table, here):
//   atomic-write    AtomicWrite / AtomicWriteAll: every temporary file written and flushed,
//                   no target replaced yet
//   atomic-publish  AtomicWriteAll: the first target of a set replaced, the others not yet
//   text-write      TextProducer (plans, sessions, autosaves, CFD dictionaries): half of the
//                   text in the temporary file
//   folder-replace  AtomicReplaceFolder: the new folder in place, the old one not yet removed
//   commit          BenderSession: a warp committed to the history, its autosave not yet
//                   written
//   recording       StreamRecorder::Append: a chunk's bytes flushed, its timestamp line not yet
//   cfd-case        WriteOpenFoamCase: one more file of the new case written in its
//                   temporary folder (the case is not in place yet)
//   cfd-results     MapCfdResults: surface.vtp and volume.vtu written in the temporary
//                   folder of the new CASE/results, flow.json not yet, nothing in place

namespace bender
{

/// The environment variable that names the point.
constexpr const char* FaultInjectionVariable = "BENDER_FAULT_AT";

/// Kills the process here when BENDER_FAULT_AT names point (see above); returns otherwise.
void FaultPoint(const char* point);

} // namespace bender

#endif
