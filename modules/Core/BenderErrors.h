#ifndef bender_BenderErrors_h
#define bender_BenderErrors_h

#include <stdexcept>
#include <string>

namespace bender
{

/// Base of the errors thrown by Bender's workflows and modules that use bender_core. what() is
/// one line that names the input and the problem, ready to show to a user.
class Error : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
  ~Error() override;
};

/// The caller asked to stop (ProgressReporter::cancel); nothing was produced or written.
/// Callers test the type (catch (const bender::Cancelled&)), never the message text.
class Cancelled : public Error
{
public:
  using Error::Error;
  ~Cancelled() override;
};

/// Unusable input: a file that cannot be read or written, a plan or parameter outside its
/// documented range. Nothing was written.
class InputError : public Error
{
public:
  using Error::Error;
  ~InputError() override;
};

/// The environment cannot run the workflow (no display and no Xvfb for rendering, ...).
class EnvironmentError : public Error
{
public:
  using Error::Error;
  ~EnvironmentError() override;
};

} // namespace bender

#endif
