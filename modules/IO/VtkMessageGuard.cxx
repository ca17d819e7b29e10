#include "VtkMessageGuard.h"

#include "StringUtil.h"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtk_loguru.h>

#include <cctype>
#include <fstream>
#include <iterator>
#include <sstream>

namespace bender
{
namespace io_detail
{

void FailMesh(const std::string& path, const std::string& problem)
{
  throw MeshIOError(QuoteBytes(DisplayName(path), 200) + ": " + QuoteBytes(problem, 400));
}

std::string TidyVtkMessage(const std::string& path, std::string message)
{
  if (message.empty())
  {
    return message;
  }
  // The display name may be the path itself (a bare file name) or contain it: search on
  // after each replacement, never at the same spot again.
  const std::string display = DisplayName(path);
  for (std::size_t at = message.find(path); !path.empty() && at != std::string::npos;
       at = message.find(path, at + display.size()))
  {
    message.replace(at, path.size(), display);
  }
  return CleanMessage(message, 200);
}

std::string ReadWholeFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    FailMesh(path, "cannot be opened for reading");
  }
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad())
  {
    FailMesh(path, "cannot read the file");
  }
  return data;
}

std::string CleanVtkMessage(const char* raw)
{
  std::string text = raw ? raw : "";
  std::istringstream lines(text);
  std::string line;
  std::string result;
  while (std::getline(lines, line))
  {
    if (line.rfind("ERROR: In ", 0) == 0 || line.rfind("Warning: In ", 0) == 0 ||
      line.rfind("Generic Warning: In ", 0) == 0)
    {
      continue;
    }
    const std::size_t marker = line.find("): ");
    if (marker != std::string::npos && line.rfind("vtk", 0) == 0)
    {
      line = line.substr(marker + 3);
    }
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back())))
    {
      line.pop_back();
    }
    if (!line.empty())
    {
      result += result.empty() ? line : "; " + line;
    }
  }
  return result.empty() ? "unknown VTK error" : result;
}

std::string OneLine(const std::string& text, std::size_t maxLength)
{
  std::string line;
  for (const char c : text)
  {
    line += (c == '\n' || c == '\r' || c == '\0') ? ' ' : c;
  }
  if (line.size() > maxLength)
  {
    line.resize(maxLength);
  }
  return line;
}

// An output window that keeps what it is given, so that messages from VTK helper objects
// without observers (parsers, vtkGenericWarningMacro) end up in our error instead of on
// stderr.
class CapturingOutputWindow : public vtkOutputWindow
{
public:
  static CapturingOutputWindow* New();
  vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override
  {
    if (!text)
    {
      return;
    }
    switch (this->GetCurrentMessageType())
    {
      case MESSAGE_TYPE_ERROR:
        this->Errors.push_back(CleanVtkMessage(text));
        break;
      case MESSAGE_TYPE_WARNING:
      case MESSAGE_TYPE_GENERIC_WARNING:
        this->Warnings.push_back(CleanVtkMessage(text));
        break;
      default:
        break;
    }
  }
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;

protected:
  CapturingOutputWindow() = default;
};
vtkStandardNewMacro(CapturingOutputWindow);

VtkMessageGuard::VtkMessageGuard()
  : Lock(Mutex())
  , Capture(vtkSmartPointer<CapturingOutputWindow>::New())
{
  this->Previous = vtkOutputWindow::GetInstance();
  vtkOutputWindow::SetInstance(this->Capture);
  this->PreviousStderrVerbosity = vtkloguru::g_stderr_verbosity;
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

VtkMessageGuard::~VtkMessageGuard()
{
  vtkLogger::SetStderrVerbosity(static_cast<vtkLogger::Verbosity>(this->PreviousStderrVerbosity));
  vtkOutputWindow::SetInstance(this->Previous);
}

void VtkMessageGuard::Watch(vtkAlgorithm* algorithm)
{
  vtkNew<vtkCallbackCommand> callback;
  callback->SetClientData(this);
  callback->SetCallback(&VtkMessageGuard::OnEvent);
  for (vtkObject* object :
    { static_cast<vtkObject*>(algorithm), static_cast<vtkObject*>(algorithm->GetExecutive()) })
  {
    object->AddObserver(vtkCommand::ErrorEvent, callback);
    object->AddObserver(vtkCommand::WarningEvent, callback);
  }
}

bool VtkMessageGuard::HasError() const
{
  return !this->Errors.empty() || !this->Capture->Errors.empty();
}

bool VtkMessageGuard::HasWarning() const
{
  return !this->Warnings.empty() || !this->Capture->Warnings.empty();
}

std::string VtkMessageGuard::Message() const
{
  const std::vector<std::string>* lists[] = {
    &this->Errors, &this->Capture->Errors, &this->Warnings, &this->Capture->Warnings
  };
  for (const auto* list : lists)
  {
    if (!list->empty())
    {
      return list->front();
    }
  }
  return {};
}

std::mutex& VtkMessageGuard::Mutex()
{
  static std::mutex mutex;
  return mutex;
}

void VtkMessageGuard::OnEvent(vtkObject*, unsigned long event, void* clientData, void* callData)
{
  auto* self = static_cast<VtkMessageGuard*>(clientData);
  const std::string text = CleanVtkMessage(static_cast<const char*>(callData));
  // The executive's "returned failure for request" says nothing the reader did not say.
  if (text.find("returned failure for request") != std::string::npos)
  {
    self->ExecutiveFailure = true;
    return;
  }
  (event == vtkCommand::ErrorEvent ? self->Errors : self->Warnings).push_back(text);
}

} // namespace io_detail
} // namespace bender
