// libFuzzer harness for the message cleaner: whatever bytes a library or a file hands it,
// the result is one line of printable ASCII of bounded length with no escape sequences.

#include "FuzzSupport.h"
#include "InputValidation.h"

#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string_view raw(reinterpret_cast<const char*>(data), size);
  const std::size_t limit = size > 0 ? 16 + data[0] : 200;
  const std::string clean = bender::io_detail::CleanMessage(raw, limit);
  bender_fuzz::CheckMessage(clean);
  if (clean.size() > limit)
  {
    std::abort();
  }
  bender_fuzz::CheckMessage(bender::io_detail::QuoteBytes(raw, limit) + ".");
  return 0;
}
