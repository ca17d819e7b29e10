#ifndef bender_VtkMessageGuard_h
#define bender_VtkMessageGuard_h

// Internal to the mesh readers and writers: VTK's messages turned into one-line MeshIOErrors
// instead of stderr, and the runners of configured VTK readers and writers. Not part of the
// module's interface.

#include "InputValidation.h"
#include "MeshIO.h"

#include <vtkErrorCode.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <mutex>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkObject;
class vtkOutputWindow;

namespace bender
{
namespace io_detail
{

/// Throws MeshIOError "NAME: problem" (file name and problem quoted: no control byte or
/// escape sequence reaches the terminal).
[[noreturn]] void FailMesh(const std::string& path, const std::string& problem);

/// A VTK message fit for a one-line error: the file's base name instead of its full path
/// (readers quote it), no control or binary bytes (readers quote garbage), at most 200 bytes.
std::string TidyVtkMessage(const std::string& path, std::string message);

/// The whole file, for the pre-validators (the size was checked against the budget). Throws
/// MeshIOError when it cannot be read.
std::string ReadWholeFile(const std::string& path);

/// VTK's "ERROR: In file, line N\nvtkClass (0x...): text\n\n" reduced to "text".
std::string CleanVtkMessage(const char* raw);

/// text on one line (newlines and NULs as spaces), at most maxLength bytes.
std::string OneLine(const std::string& text, std::size_t maxLength);

class CapturingOutputWindow;

/// For its lifetime: collects the errors and warnings of the watched VTK objects (through
/// observers, which also keeps them off the output window), routes the global output window
/// into a buffer and mutes VTK's logger on stderr, restoring both afterwards. The output
/// window and the logger are process-wide, so guards run one at a time.
class VtkMessageGuard
{
public:
  VtkMessageGuard();
  ~VtkMessageGuard();
  VtkMessageGuard(const VtkMessageGuard&) = delete;
  VtkMessageGuard& operator=(const VtkMessageGuard&) = delete;

  /// Watches an algorithm and its executive (which reports "returned failure" on its own).
  void Watch(vtkAlgorithm* algorithm);

  bool HasError() const;
  bool HasWarning() const;
  /// The first error seen, else the first warning; empty when there was neither.
  std::string Message() const;

  /// The executive reported "returned failure for request" (which says nothing more).
  bool ExecutiveFailure = false;

private:
  static std::mutex& Mutex();
  static void OnEvent(vtkObject*, unsigned long event, void* clientData, void* callData);

  std::unique_lock<std::mutex> Lock;
  vtkSmartPointer<vtkOutputWindow> Previous;
  vtkSmartPointer<CapturingOutputWindow> Capture;
  int PreviousStderrVerbosity = 0;
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;
};

// Runs a configured VTK reader and returns its output, or throws with its first error.
// warningsAreErrors: for the VTK formats, whose readers only warn about truncated data.
template<typename Reader>
vtkSmartPointer<vtkPolyData> RunReader(const std::string& path,
  Reader* reader,
  VtkMessageGuard& guard,
  bool warningsAreErrors = false)
{
  reader->Update();
  const unsigned long code = reader->GetErrorCode();
  if (guard.HasError() || code != 0 || guard.ExecutiveFailure ||
    (warningsAreErrors && guard.HasWarning()))
  {
    std::string message = TidyVtkMessage(path, guard.Message());
    if (message.empty())
    {
      message = std::string("read error (") +
        vtkErrorCode::GetStringFromErrorCode(static_cast<unsigned long>(code)) + ")";
    }
    FailMesh(path, message);
  }
  vtkSmartPointer<vtkPolyData> output = reader->GetOutput();
  if (!output || output->GetNumberOfPoints() == 0)
  {
    const std::string message = TidyVtkMessage(path, guard.Message());
    FailMesh(
      path, message.empty() ? "no points in the file" : "no points in the file (" + message + ")");
  }
  // Detach from the reader so that the caller owns plain data.
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(output);
  return mesh;
}

// Runs a configured VTK writer (vtkWriter or vtkXMLWriter), reporting its first error.
template<typename Writer>
bool RunWriter(Writer* writer, std::string& problem)
{
  VtkMessageGuard guard;
  guard.Watch(writer);
  const int ok = writer->Write();
  if (!ok || guard.HasError() || writer->GetErrorCode() != 0)
  {
    problem = guard.Message().empty() ? std::string() : CleanMessage(guard.Message());
    if (problem.empty())
    {
      problem = std::string("write error (") +
        vtkErrorCode::GetStringFromErrorCode(writer->GetErrorCode()) + ")";
    }
    return false;
  }
  return true;
}
} // namespace io_detail
} // namespace bender

#endif
