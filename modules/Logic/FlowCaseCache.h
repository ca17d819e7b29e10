#ifndef bender_FlowCaseCache_h
#define bender_FlowCaseCache_h

// The cache of flow cases (issue 23, the Flow panel): one OpenFOAM case folder per content,
// CACHE/<key>, where the key is a hash of every file WriteOpenFoamCase wrote (the CFD-ready
// surface in metres, the dictionaries, bender-case.json: the shape the plan made and every
// case option). The same shape with the same options is the same case: it is solved once, and
// its results are found again (after an undo, a redo, a second window run, a restart).

#include "CfdCase.h"
#include "LabelledSurface.h"

#include <string>

namespace bender
{

/// A case of the cache, written and ready to run, or already run.
struct CachedFlowCase
{
  std::string key;           ///< FlowCaseKey: 32 hexadecimal digits
  std::string caseDirectory; ///< CACHE/<key>
  CfdCaseResult written;     ///< what WriteOpenFoamCase wrote (caseDirectory as above)
  /// Its results are there (results/flow.json and results/surface.vtp, from an earlier run):
  /// nothing to solve.
  bool solved = false;
};

/// The content key of a written case: the content hash (ContentHash.h) of the relative path
/// and the bytes of each file of `written.written`, in name order. Throws InputError naming a
/// file it cannot read.
std::string FlowCaseKey(const CfdCaseResult& written);

/// Whether `caseDirectory` holds the results of a finished run (results/flow.json readable by
/// ReadCfdFlowResults and results/surface.vtp present).
bool HasFlowResults(const std::string& caseDirectory);

/// Writes the case of `surface` with `options` (caseDirectory and force are the cache's) into
/// `cacheDirectory` (created when missing) and files it under its key. When a case of that key
/// has results, the new one is dropped and that one returned (solved); otherwise it takes the
/// key's place (replacing what an interrupted run left there). Throws InputError for a surface
/// or options WriteOpenFoamCase refuses and for a cache folder that cannot be written.
CachedFlowCase StoreFlowCase(const LabelledSurface& surface,
  const CfdCaseOptions& options,
  const std::string& cacheDirectory);

} // namespace bender

#endif
