// libFuzzer harness for the session (autosave) file reader, ReadSessionFile: any bytes give a
// snapshot or a SessionFileError of one clean line. A snapshot read is written back with
// WriteSessionFile and read again: the writer must take whatever the reader accepted, and the
// second reading must give the same session (names, frame, plan, volume, segmentation, ribbon).

#include "FuzzSupport.h"
#include "SessionAutosave.h"
#include "WarpPlanIO.h"

#include <cstdio>
#include <cstdlib>

namespace
{

void Fail(const char* what)
{
  std::fprintf(stderr, "finding: %s\n", what);
  std::abort();
}

bool SameSession(const bender::SessionSnapshot& a, const bender::SessionSnapshot& b)
{
  if (a.sourcePath != b.sourcePath || a.surfaceName != b.surfaceName || a.frame != b.frame ||
    bender::SerializeWarpPlan(a.plan) != bender::SerializeWarpPlan(b.plan) ||
    a.volume.has_value() != b.volume.has_value() ||
    a.segmentation.has_value() != b.segmentation.has_value() ||
    a.ribbon.has_value() != b.ribbon.has_value())
  {
    return false;
  }
  if (a.volume &&
    (a.volume->path != b.volume->path || a.volume->name != b.volume->name ||
      a.volume->maskPath != b.volume->maskPath ||
      a.volume->dicomSeriesUid != b.volume->dicomSeriesUid ||
      !bender::SameVolumeGeometry(a.volume->geometry, b.volume->geometry)))
  {
    return false;
  }
  if (a.ribbon &&
    (a.ribbon->radius != b.ribbon->radius || a.ribbon->vesselRadius != b.ribbon->vesselRadius ||
      a.ribbon->ribbon.extraTurns != b.ribbon->ribbon.extraTurns))
  {
    return false;
  }
  if (a.segmentation &&
    (a.segmentation->segmentation.lower != b.segmentation->segmentation.lower ||
      a.segmentation->segmentation.seeds.size() != b.segmentation->segmentation.seeds.size() ||
      a.segmentation->surface.targetTriangles != b.segmentation->surface.targetTriangles))
  {
    return false;
  }
  return true;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string path = bender_fuzz::WriteInput("autosave.bender-session.json", data, size);
  bender::SessionSnapshot read;
  try
  {
    read = bender::ReadSessionFile(path);
  }
  catch (const bender::SessionFileError& e)
  {
    bender_fuzz::CheckMessage(e.what());
    return 0;
  }
  const std::string copy = (bender_fuzz::ScratchFolder() / "copy.bender-session.json").string();
  try
  {
    bender::WriteSessionFile(read, copy);
  }
  catch (const bender::SessionFileError& e)
  {
    std::fprintf(stderr, "%s\n", e.what());
    Fail("a session the reader accepted cannot be written");
  }
  bender::SessionSnapshot again;
  try
  {
    again = bender::ReadSessionFile(copy);
  }
  catch (const bender::SessionFileError& e)
  {
    std::fprintf(stderr, "%s\n", e.what());
    Fail("a session written from one read cannot be read");
  }
  if (!SameSession(read, again))
  {
    Fail("a session changed in a write and read");
  }
  return 0;
}
