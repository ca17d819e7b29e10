#include "FileIdentity.h"

#include <filesystem>
#include <system_error>

namespace bender
{

bool SameFile(const std::string& a, const std::string& b)
{
  if (a.empty() || b.empty())
  {
    return false;
  }
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec))
  {
    const bool same = fs::equivalent(a, b, ec);
    if (!ec)
    {
      return same;
    }
  }
  const fs::path na = fs::weakly_canonical(fs::absolute(a, ec), ec);
  std::error_code ec2;
  const fs::path nb = fs::weakly_canonical(fs::absolute(b, ec2), ec2);
  if (ec || ec2)
  {
    // Neither canonical form is available: compare the lexical forms (no file system access).
    const fs::path la = fs::absolute(a, ec).lexically_normal();
    const fs::path lb = fs::absolute(b, ec2).lexically_normal();
    return !ec && !ec2 && la == lb;
  }
  return na == nb;
}

std::string AbsolutePath(const std::string& path)
{
  std::error_code ec;
  const auto absolute = std::filesystem::absolute(path, ec);
  return ec ? path : absolute.lexically_normal().string();
}

} // namespace bender
