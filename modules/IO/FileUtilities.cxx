#include "FileUtilities.h"

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include <unistd.h>

namespace fs = std::filesystem;

namespace bender
{
namespace io_detail
{

bool CheckReadableFile(const std::string& path, std::uintmax_t& size, std::string& problem)
{
  size = 0;
  if (path.empty())
  {
    problem = "empty file name";
    return false;
  }
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status))
  {
    problem = "no such file";
    return false;
  }
  if (fs::is_directory(status))
  {
    problem = "is a folder, not a file";
    return false;
  }
  if (!fs::is_regular_file(status))
  {
    problem = "not a regular file";
    return false;
  }
  size = fs::file_size(path, ec);
  if (ec)
  {
    problem = "cannot read the file size (" + ec.message() + ")";
    return false;
  }
  std::ifstream probe(path, std::ios::binary);
  if (!probe)
  {
    problem = std::string("cannot be opened for reading (") + std::strerror(errno) + ")";
    return false;
  }
  if (size == 0)
  {
    problem = "empty file (0 bytes)";
    return false;
  }
  return true;
}

} // namespace io_detail
} // namespace bender
