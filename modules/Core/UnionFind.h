#ifndef bender_UnionFind_h
#define bender_UnionFind_h

// Disjoint sets over the elements 0, 1, ..., Size() - 1 (union-find), the one used by the
// triangle components of the mesh code, the vessel clip, the centerline branches and the
// run-length components of the segmentation. The representative of a set is its smallest
// element, so that results do not depend on the order of the joins: labelling the sets in
// order of their representatives gives the order of their first elements.
// Find halves the paths it walks. Index is the element type: std::uint32_t halves the memory
// of very large sets (the runs of a volume), std::size_t otherwise (UnionFind).

#include <cstddef>
#include <cstdint>
#include <vector>

namespace bender
{

template<typename Index>
class BasicUnionFind
{
public:
  /// n singleton sets {0}, {1}, ..., {n - 1}.
  explicit BasicUnionFind(std::size_t n = 0)
    : Parent(n)
    , Count(n)
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      this->Parent[i] = static_cast<Index>(i);
    }
  }

  /// Appends the singleton {Size()} and returns its element.
  Index Add()
  {
    const auto i = static_cast<Index>(this->Parent.size());
    this->Parent.push_back(i);
    ++this->Count;
    return i;
  }

  /// The representative (smallest element) of i's set.
  Index Find(Index i)
  {
    while (this->Parent[i] != i)
    {
      this->Parent[i] = this->Parent[this->Parent[i]];
      i = this->Parent[i];
    }
    return i;
  }

  /// Merges the sets of a and b; true when they were different sets.
  bool Join(Index a, Index b)
  {
    a = this->Find(a);
    b = this->Find(b);
    if (a == b)
    {
      return false;
    }
    if (b < a)
    {
      this->Parent[a] = b;
    }
    else
    {
      this->Parent[b] = a;
    }
    --this->Count;
    return true;
  }

  /// The number of elements.
  std::size_t Size() const { return this->Parent.size(); }
  /// The number of sets.
  std::size_t Sets() const { return this->Count; }

private:
  std::vector<Index> Parent;
  std::size_t Count = 0;
};

using UnionFind = BasicUnionFind<std::size_t>;

} // namespace bender

#endif
