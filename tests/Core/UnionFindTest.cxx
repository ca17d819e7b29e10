#include "UnionFind.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

namespace
{

// Brute force: labels relabelled on every join.
struct Labels
{
  std::vector<std::size_t> label;
  void Join(std::size_t a, std::size_t b)
  {
    const std::size_t from = this->label[b], to = this->label[a];
    for (auto& l : this->label)
    {
      if (l == from)
      {
        l = to;
      }
    }
  }
};

TEST(UnionFind, JoinsAndCountsSets)
{
  bender::UnionFind sets(6);
  EXPECT_EQ(sets.Sets(), 6u);
  EXPECT_TRUE(sets.Join(4, 2));
  EXPECT_TRUE(sets.Join(2, 5));
  EXPECT_FALSE(sets.Join(5, 4));
  EXPECT_EQ(sets.Sets(), 4u);
  EXPECT_EQ(sets.Find(5), 2u); // the smallest element represents its set
  EXPECT_EQ(sets.Find(4), 2u);
  EXPECT_EQ(sets.Find(0), 0u);
  EXPECT_NE(sets.Find(1), sets.Find(3));
}

TEST(UnionFind, SingletonsAtFirst)
{
  bender::UnionFind sets(5);
  EXPECT_EQ(sets.Size(), 5u);
  EXPECT_EQ(sets.Sets(), 5u);
  for (std::size_t i = 0; i < 5; ++i)
  {
    EXPECT_EQ(sets.Find(i), i);
  }
}

TEST(UnionFind, JoinsSayWhetherTheSetsDiffered)
{
  bender::UnionFind sets(4);
  EXPECT_TRUE(sets.Join(3, 1));
  EXPECT_FALSE(sets.Join(1, 3));
  EXPECT_TRUE(sets.Join(2, 3));
  EXPECT_FALSE(sets.Join(2, 1));
  EXPECT_EQ(sets.Sets(), 2u);
  EXPECT_EQ(sets.Find(3), sets.Find(2));
  EXPECT_NE(sets.Find(0), sets.Find(1));
}

TEST(UnionFind, RandomJoinsMatchBruteForceAndTheSmallestRepresents)
{
  std::mt19937 random(7);
  for (int trial = 0; trial < 20; ++trial)
  {
    const std::size_t n = 1 + random() % 200;
    bender::UnionFind sets(n);
    bender::BasicUnionFind<std::uint32_t> small(n);
    Labels brute{ std::vector<std::size_t>(n) };
    for (std::size_t i = 0; i < n; ++i)
    {
      brute.label[i] = i;
    }
    const std::size_t joins = random() % (2 * n);
    for (std::size_t j = 0; j < joins; ++j)
    {
      const std::size_t a = random() % n, b = random() % n;
      const bool differed = brute.label[a] != brute.label[b];
      EXPECT_EQ(sets.Join(a, b), differed);
      EXPECT_EQ(small.Join(std::uint32_t(a), std::uint32_t(b)), differed);
      brute.Join(a, b);
    }
    std::size_t distinct = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      std::size_t smallest = i;
      for (std::size_t k = 0; k < n; ++k)
      {
        EXPECT_EQ(sets.Find(i) == sets.Find(k), brute.label[i] == brute.label[k]);
        if (brute.label[k] == brute.label[i] && k < smallest)
        {
          smallest = k;
        }
      }
      EXPECT_EQ(sets.Find(i), smallest);
      EXPECT_EQ(small.Find(std::uint32_t(i)), smallest);
      distinct += smallest == i ? 1 : 0;
    }
    EXPECT_EQ(sets.Sets(), distinct);
    EXPECT_EQ(small.Sets(), distinct);
  }
}

TEST(UnionFind, AddAppendsASingleton)
{
  bender::BasicUnionFind<std::uint32_t> sets;
  EXPECT_EQ(sets.Size(), 0u);
  EXPECT_EQ(sets.Add(), 0u);
  EXPECT_EQ(sets.Add(), 1u);
  EXPECT_EQ(sets.Add(), 2u);
  EXPECT_TRUE(sets.Join(2, 0));
  EXPECT_EQ(sets.Sets(), 2u);
  EXPECT_EQ(sets.Find(2), 0u);
  EXPECT_EQ(sets.Find(1), 1u);
}

} // namespace
