#include "Progress.h"

namespace bender
{

// Out of line so that every library shares one type_info and vtable for each error.
Error::~Error() = default;
Cancelled::~Cancelled() = default;
InputError::~InputError() = default;
EnvironmentError::~EnvironmentError() = default;

void ProgressReporter::ThrowIfCancelled(const std::string& stage) const
{
  if (this->Cancelled())
  {
    throw bender::Cancelled("cancelled during " + stage);
  }
}

} // namespace bender
