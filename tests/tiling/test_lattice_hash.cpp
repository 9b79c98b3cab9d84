#include <gtest/gtest.h>

#include <map>
#include <numeric>
#include <set>

#include "base/error.hpp"
#include "tiling/direct_tiling.hpp"
#include "tiling/lattice_hash.hpp"
#include "base/random.hpp"

using namespace tilekit;

TEST(PermutationHash, TableIsAPermutationFixedByTheSeed) {
  PermutationHash a(256, 7), b(256, 7), c(256, 8);
  std::vector<std::uint32_t> sorted = a.table();
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t i = 0; i < 256; ++i) EXPECT_EQ(sorted[i], i);
  EXPECT_EQ(a.table(), b.table());
  EXPECT_NE(a.table(), c.table());
}

TEST(PermutationHash, Eq31To34ArePeriodicWithPeriodNAlsoForNegativeCoordinates) {
  PermutationHash h(256, 3);
  SplitMix64 rng(1);
  for (int k = 0; k < 2000; ++k) {
    const std::int64_t x = std::int64_t(rng.below(1u << 30)) - (1 << 29), y = std::int64_t(rng.below(1000)) - 500,
                       z = std::int64_t(rng.below(1000)) - 500;
    EXPECT_EQ(h(x), h(x + 256));
    EXPECT_EQ(h(x), h.table()[std::size_t(((x % 256) + 256) % 256)]);  // eq. (3.1)
    EXPECT_EQ(h(x, y), h(x - 256, y));
    EXPECT_EQ(h(x, y), h(x, y + 256));
    EXPECT_EQ(h(x, y), h.table()[(h(x) + h.mod(y)) % 256]);  // eq. (3.3)
    EXPECT_EQ(h(x, y, z), h(x, y, z + 512));
    EXPECT_EQ(h(x, y, z), h.table()[(h(x, y) + h.mod(z)) % 256]);  // eq. (3.4)
    EXPECT_EQ(h.two_tables(x, y), h.two_tables(x + 256, y - 256));
    EXPECT_LT(h.two_tables(x, y), 256u);
  }
}

TEST(PermutationHash, TwoDimensionalHashTakesEveryValueOncePerColumnOfThePeriod) {
  PermutationHash h(100, 5);
  for (std::int64_t x = 0; x < 100; ++x) {
    std::set<std::uint32_t> seen;
    for (std::int64_t y = 0; y < 100; ++y) seen.insert(h(x, y));
    EXPECT_EQ(seen.size(), 100u);
  }
}

TEST(LongPeriodHash, ThesisDesignHasRange24AndA180EntryTable) {
  LongPeriodHash h = LongPeriodHash::thesis_tiling_hash(1);
  EXPECT_EQ(h.range(), 24u);
  auto sizes = h.sizes();
  EXPECT_EQ(sizes, (std::vector<std::uint32_t>{24, 17, 19, 23, 29, 31, 37}));
  EXPECT_EQ(std::accumulate(sizes.begin(), sizes.end(), 0u), 180u);  // thesis sec. 3.4.3
}

TEST(LongPeriodHash, ThesisPeriodIs5930659848Arithmetically) {
  LongPeriodHash h = LongPeriodHash::thesis_tiling_hash(1);
  const std::uint64_t product = 17ull * 19 * 23 * 24 * 29 * 31 * 37;
  EXPECT_EQ(product, 5930659848ull);
  EXPECT_GT(product, 0xffffffffull);  // "more than the 32-bit integer range"
  auto sizes = h.sizes();
  for (std::size_t i = 0; i < sizes.size(); ++i)
    for (std::size_t j = i + 1; j < sizes.size(); ++j) EXPECT_EQ(std::gcd(sizes[i], sizes[j]), 1u);
  EXPECT_EQ(h.period(), product);  // lcm of pairwise coprime sizes is their product
}

TEST(LongPeriodHash, PeriodIsExactlyTheLcmNotAProperDivisor) {
  LongPeriodHash h = LongPeriodHash::thesis_tiling_hash(11);
  const std::int64_t period = std::int64_t(h.period());
  SplitMix64 rng(2);
  for (int k = 0; k < 2000; ++k) {
    const std::int64_t x = std::int64_t(rng.below(1ull << 40)) - (1ll << 39), y = std::int64_t(rng.below(1 << 20));
    ASSERT_EQ(h(x), h(x + period));  // eq. (3.5)
    ASSERT_EQ(h(x, y), h(x - period, y));
    ASSERT_EQ(h(x, y), h(x, y + period));  // eq. (3.6)
    ASSERT_EQ(h(x, y, 5), h(x, y, 5 + period));
    ASSERT_LT(h(x, y), 24u);
  }
  // For every prime factor q of the period, period / q is not a period: the shift moves only
  // the table whose size q divides, and some x sees a different sum modulo 24.
  for (std::int64_t q : {2, 3, 17, 19, 23, 29, 31, 37}) {
    bool differs = false;
    for (std::int64_t x = 0; x < 5000 && !differs; ++x) differs = h(x) != h(x + period / q);
    EXPECT_TRUE(differs) << "period / " << q;
  }
}

TEST(LongPeriodHash, ForColoursKeepsTheThesisDesignForDivisorsOf24AndStaysCoprime) {
  for (std::uint32_t c : {2u, 3u, 4u, 6u, 8u, 12u, 24u})
    EXPECT_EQ(LongPeriodHash::for_colours(c, 1).period(), 5930659848ull);
  for (std::uint32_t c : {5u, 7u, 9u, 17u, 37u, 100u, 255u}) {
    LongPeriodHash h = LongPeriodHash::for_colours(c, 1);
    EXPECT_EQ(h.range() % c, 0u) << c;
    EXPECT_GE(h.range(), 24u);
    auto s = h.sizes();
    std::uint64_t product = 1;
    for (std::size_t i = 0; i < s.size(); ++i) {
      product *= s[i];
      for (std::size_t j = i + 1; j < s.size(); ++j) EXPECT_EQ(std::gcd(s[i], s[j]), 1u) << c;
    }
    EXPECT_EQ(h.period(), product) << c;
  }
}

TEST(ColourHash, RowEvaluationEqualsPointEvaluation) {
  for (HashKind kind : {HashKind::Permutation, HashKind::LongPeriod})
    for (std::uint32_t c : {2u, 3u, 7u}) {
      ColourHash h(kind, c, 99);
      ColourHash::RowCache cache;
      const std::int64_t x0 = -1234567;
      h.prepare(cache, x0, 600);
      std::vector<std::uint16_t> row(600);
      for (std::int64_t y : {-300ll, -1ll, 0ll, 5ll, 123456789ll}) {
        h.row(cache, y, row.data());
        for (std::size_t k = 0; k < row.size(); ++k) ASSERT_EQ(row[k], h.colour(x0 + std::int64_t(k), y));
      }
    }
}

// The incremental row evaluations (16-bit sums with any stride, 8-bit sums in chunks of 32
// columns) equal the point evaluation of thesis eq. (3.3) / (3.6) everywhere: negative
// coordinates, rows that do not end on a chunk, strides that share factors with the table sizes.
TEST(ColourHash, IncrementalRowsWithStridesAndBytesEqualPointEvaluation) {
  for (HashKind kind : {HashKind::Permutation, HashKind::LongPeriod})
    for (std::uint32_t c : {1u, 2u, 3u, 5u, 6u, 8u, 24u, 40u, 300u}) {
      const ColourHash h(kind, c, 7);
      if (kind == HashKind::LongPeriod && c <= 24) {
        EXPECT_TRUE(h.bytes_suffice()) << c;  // sums below 47 + 150
      }
      if (kind == HashKind::Permutation) {
        EXPECT_EQ(h.bytes_suffice(), 256 % c == 0) << c;  // one table of 256 entries
      }
      if (c == 300) {
        EXPECT_FALSE(h.bytes_suffice());
      }
      for (std::int64_t stride : {1, 2, 3, 17}) {
        ColourHash::RowCache cache;
        const std::int64_t x0 = -1000003;
        h.prepare(cache, x0, 333, stride);
        std::vector<std::uint16_t> row(333);
        for (std::int64_t y : {-77ll, 0ll, 999999937ll}) {
          h.row(cache, y, row.data());
          for (std::size_t k = 0; k < row.size(); ++k)
            ASSERT_EQ(row[k], h.colour(x0 + std::int64_t(k) * stride, y)) << c << " stride " << stride;
          if (stride == 1 && h.bytes_suffice()) {
            const std::uint8_t* bytes = h.row_bytes(cache, y);
            for (std::size_t k = 0; k < row.size(); ++k) ASSERT_EQ(bytes[k], row[k]) << c << " column " << k;
          }
        }
      }
    }
}

TEST(DirectCornerTiling, FillIsTheSameOnAnyThreadCountAndEqualsTileByTile) {
  for (HashKind kind : {HashKind::Permutation, HashKind::LongPeriod})
    for (std::uint32_t c : {2u, 3u, 17u}) {
      const DirectCornerTiling t(c, kind, 3);
      const int rows = 37, cols = 600;
      std::vector<TileIndex> one(std::size_t(rows) * cols), three(one.size());
      t.fill(-300, -5, rows, cols, one.data(), 1);
      t.fill(-300, -5, rows, cols, three.data(), 3);
      EXPECT_EQ(one, three);
      for (int r = 0; r < rows; r += 7)
        for (int k = 0; k < cols; ++k) ASSERT_EQ(one[std::size_t(r) * cols + std::size_t(k)], t.tile(k - 300, r - 5));
    }
}

TEST(ColourHash, PermutationHashGivesEveryColourExactlyEquallyOftenOverItsPeriod) {
  for (std::uint32_t c : {3u, 5u, 7u}) {
    ColourHash h(HashKind::Permutation, c, 4);
    const std::int64_t n = std::int64_t(h.period());
    EXPECT_EQ(n % c, 0) << "table size is a multiple of C";
    std::vector<std::int64_t> count(c, 0);
    for (std::int64_t x = 0; x < n; ++x)
      for (std::int64_t y = 0; y < n; ++y) ++count[h.colour(x, y)];
    for (std::uint32_t k = 0; k < c; ++k) EXPECT_EQ(count[k], n * n / c);
  }
}

TEST(ColourHash, LongPeriodHashIsCloseToUniform) {
  for (std::uint32_t c : {2u, 3u, 5u, 8u}) {
    ColourHash h(HashKind::LongPeriod, c, 4);
    std::vector<double> count(c, 0);
    const int n = 400;
    for (int x = 0; x < n; ++x)
      for (int y = 0; y < n; ++y) ++count[h.colour(x, y)];
    for (std::uint32_t k = 0; k < c; ++k) EXPECT_NEAR(count[k] / (n * n), 1.0 / c, 0.01) << c;
  }
}

TEST(HashKind, UnknownNameIsAnInputError) {
  EXPECT_EQ(parse_hash_kind("perm"), HashKind::Permutation);
  EXPECT_EQ(parse_hash_kind("long-period"), HashKind::LongPeriod);
  EXPECT_THROW(parse_hash_kind("md5"), InputError);
}
