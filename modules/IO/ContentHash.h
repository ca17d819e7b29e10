#ifndef bender_ContentHash_h
#define bender_ContentHash_h

// The one content hash of Bender: an MD5 digest (32 hexadecimal digits) of bytes fed in
// pieces. It names content, never guards it: the flow cache's keys (FlowCaseKey: the files of
// a written case) and a sweep's candidate hashes (SweepCandidateHash: the surface and the
// inputs of a candidate) are both made here, so that the same content has one name.

#include <cstddef>
#include <memory>
#include <string>

namespace bender
{

class ContentHash
{
public:
  ContentHash();
  ~ContentHash();
  ContentHash(const ContentHash&) = delete;
  ContentHash& operator=(const ContentHash&) = delete;

  /// Adds `size` bytes at `data` (any size, in as many pieces as wanted: the digest depends
  /// only on the bytes and their order).
  void Add(const void* data, std::size_t size);
  void Add(const std::string& bytes);
  /// Adds the whole content of file `path`; false (the bytes read so far added) when it cannot
  /// be read.
  bool AddFile(const std::string& path);

  /// The digest of everything added, 32 lower-case hexadecimal digits. Ends the hash: nothing
  /// may be added afterwards (Add and AddFile then throw std::logic_error).
  std::string Finish();

private:
  struct State;
  std::unique_ptr<State> Md5;
};

} // namespace bender

#endif
