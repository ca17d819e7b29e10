#ifndef bender_VtkErrorWatch_h
#define bender_VtkErrorWatch_h

// Error and warning assertions for tests of VTK classes: VTK's own vtkTest::ErrorObserver
// attached to an algorithm and its executive, so that a test asserts the errors it expects
// (by a part of the message) and fails on any it did not expect. While attached, the
// messages do not reach the VTK output window (stderr).

#include <vtkAlgorithm.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkTestErrorObserver.h>

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace bendertest
{

class VtkErrorWatch
{
public:
  /// Watches algorithm (and the executive that reports its failed requests).
  explicit VtkErrorWatch(vtkAlgorithm* algorithm)
  {
    this->Watch(algorithm);
    this->Watch(algorithm->GetExecutive());
  }
  VtkErrorWatch(const VtkErrorWatch&) = delete;
  VtkErrorWatch& operator=(const VtkErrorWatch&) = delete;

  /// Fails the test when errors or warnings were reported and not checked.
  ~VtkErrorWatch()
  {
    const std::string left = this->Messages();
    if (!left.empty())
    {
      ADD_FAILURE() << "unexpected VTK error or warning: " << left;
    }
    for (const auto& [object, tag] : this->Tags)
    {
      object->RemoveObserver(tag);
    }
  }

  /// Succeeds when an error whose text contains part was reported since the last check;
  /// the messages are then cleared.
  ::testing::AssertionResult ExpectError(const std::string& part)
  {
    const std::string errors = this->Errors();
    this->Observer->Clear();
    if (errors.empty())
    {
      return ::testing::AssertionFailure()
        << "no VTK error reported; expected one containing \"" << part << "\"";
    }
    if (errors.find(part) == std::string::npos)
    {
      return ::testing::AssertionFailure()
        << "the VTK error does not contain \"" << part << "\": " << errors;
    }
    return ::testing::AssertionSuccess();
  }

  /// Succeeds when no error or warning was reported since the last check.
  ::testing::AssertionResult ExpectNone()
  {
    const std::string messages = this->Messages();
    this->Observer->Clear();
    if (!messages.empty())
    {
      return ::testing::AssertionFailure() << "unexpected VTK error or warning: " << messages;
    }
    return ::testing::AssertionSuccess();
  }

private:
  vtkNew<vtkTest::ErrorObserver> Observer;
  std::vector<std::pair<vtkSmartPointer<vtkObject>, unsigned long>> Tags;

  void Watch(vtkObject* object)
  {
    if (!object)
    {
      return;
    }
    this->Tags.emplace_back(object, object->AddObserver(vtkCommand::ErrorEvent, this->Observer));
    this->Tags.emplace_back(object, object->AddObserver(vtkCommand::WarningEvent, this->Observer));
  }

  std::string Errors()
  {
    return this->Observer->GetError() ? this->Observer->GetErrorMessage() : "";
  }

  std::string Messages()
  {
    std::string text = this->Errors();
    if (this->Observer->GetWarning())
    {
      text += (text.empty() ? "" : " ") + this->Observer->GetWarningMessage();
    }
    return text;
  }
};

} // namespace bendertest

#endif
