// The one stable hash (base/hash.hpp): published FNV-1a 64 test vectors (Fowler, Noll and Vo;
// the IETF draft "The FNV Non-Cryptographic Hash Algorithm" lists "" and "a", "foobar") and the
// MurmurHash3 fmix64 finaliser over them, values computed once outside this code in Python.
// These values are stored in files (checksums, fingerprints): a change here breaks old files.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "base/hash.hpp"

using namespace tilekit;

TEST(StableHashGolden, Fnv1a64PublishedVectors) {
  EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ull);  // the offset basis
  EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv1a64("foobar"), 0x85944171f73967e8ull);
  EXPECT_EQ(fnv1a64("tilekit"), 0xf41e38cb82beb78bull);
}

TEST(StableHashGolden, FinaliserOverFnv) {
  EXPECT_EQ(stable_hash64(""), 0xefd01f60ba992926ull);
  EXPECT_EQ(stable_hash64("a"), 0x82a2a958a9bece5bull);
  EXPECT_EQ(stable_hash64("foobar"), 0x2c22194922d1672bull);
}

TEST(StableHashGolden, IntegersAreHashedAsLittleEndianBytes) {
  // add(v, n): the n low bytes of v, least significant first.
  EXPECT_EQ(StableHash().add(0x0102030405060708ull).fnv(), 0x0c6d4496e17859d5ull);
  EXPECT_EQ(StableHash().add(0x0102030405060708ull, 4).fnv(), 0x106ce2c22d355d45ull);
  EXPECT_EQ(StableHash().add(0x0102030405060708ull, 4).fnv(),
            StableHash().add(std::string("\x08\x07\x06\x05", 4)).fnv());
  EXPECT_EQ(StableHash().add(0, 0).fnv(), fnv1a64(""));  // zero bytes: the offset basis
}

TEST(StableHashGolden, PiecesHashLikeTheWhole) {
  EXPECT_EQ(StableHash().add("foo").add("bar").fnv(), fnv1a64("foobar"));
  EXPECT_EQ(StableHash().add("foo").add("bar").mixed(), stable_hash64("foobar"));
}
