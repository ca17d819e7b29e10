#include "ContentHash.h"

#include <vtksys/MD5.h>

#include <algorithm>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace bender
{

struct ContentHash::State
{
  vtksysMD5* md5 = vtksysMD5_New();
  bool finished = false;
  ~State() { vtksysMD5_Delete(this->md5); }
};

ContentHash::ContentHash()
  : Md5(std::make_unique<State>())
{
  vtksysMD5_Initialize(this->Md5->md5);
}

ContentHash::~ContentHash() = default;

void ContentHash::Add(const void* data, std::size_t size)
{
  if (this->Md5->finished)
  {
    throw std::logic_error("ContentHash: bytes added after Finish");
  }
  // vtksysMD5_Append takes an int length: pieces of at most 16 MiB.
  constexpr std::size_t Chunk = 1 << 24;
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t at = 0; at < size; at += Chunk)
  {
    vtksysMD5_Append(this->Md5->md5, bytes + at, static_cast<int>(std::min(Chunk, size - at)));
  }
}

void ContentHash::Add(const std::string& bytes)
{
  this->Add(bytes.data(), bytes.size());
}

bool ContentHash::AddFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    return false;
  }
  std::vector<char> buffer(1 << 16);
  while (in.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) || in.gcount() > 0)
  {
    this->Add(buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  return !in.bad();
}

std::string ContentHash::Finish()
{
  if (this->Md5->finished)
  {
    throw std::logic_error("ContentHash: Finish called twice");
  }
  this->Md5->finished = true;
  char hex[33] = {};
  vtksysMD5_FinalizeHex(this->Md5->md5, hex);
  return std::string(hex, 32);
}

} // namespace bender
