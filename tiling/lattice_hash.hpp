#pragma once
// Hash functions over the integer lattice (thesis sec. 3.4): traditional hashes based on one
// permutation table (eq. 3.1-3.4) and long-period combined hashes (eq. 3.5-3.7), plus
// ColourHash, the lattice hash reduced to C colours that the direct stochastic tiling
// algorithms use (thesis sec. 3.4.3). Coordinates are 64-bit; x % N is the floored modulo,
// so every hash is periodic over all of Z (negative coordinates included).
#include <cstdint>
#include <string>
#include <vector>

// Hot loops compiled for AVX2 and for the baseline instruction set; the loader picks the one the
// CPU runs. GCC only: clang 14 leaves a member function's clones unresolved at link time (the
// clang builds are the sanitizer and fuzz builds, where the baseline loop is enough).
#if defined(__GNUC__) && !defined(__clang__)
#define TILEKIT_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define TILEKIT_CLONES
#endif

namespace tilekit {

enum class HashKind { Permutation, LongPeriod };

// "perm" or "long-period"; throws InputError otherwise.
HashKind parse_hash_kind(const std::string& name);
const char* hash_kind_name(HashKind k);

// A permutation table P of size N (thesis sec. 3.4.1), shuffled from an explicit seed.
class PermutationHash {
 public:
  PermutationHash(std::uint32_t size, std::uint64_t seed);

  std::uint32_t size() const { return n_; }
  std::uint32_t range() const { return n_; }
  std::uint64_t period() const { return n_; }
  const std::vector<std::uint32_t>& table() const { return p_; }

  // thesis eq. (3.1): h(x) = P[x % N]
  std::uint32_t operator()(std::int64_t x) const { return p_[mod(x)]; }
  // thesis eq. (3.3): h(x, y) = P[(P[x % N] + y) % N]
  std::uint32_t operator()(std::int64_t x, std::int64_t y) const { return p_[(p_[mod(x)] + mod(y)) % n_]; }
  // thesis eq. (3.4): h(x, y, z) = P[(P[(P[x % N] + y) % N] + z) % N]
  std::uint32_t operator()(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return p_[(p_[(p_[mod(x)] + mod(y)) % n_] + mod(z)) % n_];
  }
  // thesis eq. (3.2): h(x, y) = (P_x[x % N] + P_y[y % N]) % N, with a second table P_y.
  std::uint32_t two_tables(std::int64_t x, std::int64_t y) const { return (p_[mod(x)] + q_[mod(y)]) % n_; }

  std::uint64_t mod(std::int64_t x) const {
    std::int64_t r = x % std::int64_t(n_);
    return std::uint64_t(r < 0 ? r + n_ : r);
  }

 private:
  std::uint32_t n_;
  std::vector<std::uint32_t> p_, q_;
};

// A combined hash of M permutation tables of sizes N_0..N_{M-1}, reduced modulo N_j
// (thesis eq. 3.5-3.7). Its period is the least common multiple of the sizes.
class LongPeriodHash {
 public:
  LongPeriodHash(std::vector<std::uint32_t> sizes, std::size_t final_index, std::uint64_t seed);

  // The design of thesis sec. 3.4.3: range 24 (the lcm of 2, 3, 4, 6, 8 colours) and the
  // primes 17, 19, 23, 29, 31, 37; period 17*19*23*24*29*31*37 = 5,930,659,848.
  static LongPeriodHash thesis_tiling_hash(std::uint64_t seed);
  // The same design for C colours (thesis sec. 3.4.2.4): range R = the smallest multiple of C
  // that is >= 24 (R = 24 for every C dividing 24, i.e. exactly the thesis design), and the
  // primes 17..37, where a prime dividing R is replaced by the next prime above 37 that does not.
  static LongPeriodHash for_colours(std::uint32_t c, std::uint64_t seed);

  std::uint32_t range() const { return tables_[final_].size(); }
  std::uint64_t period() const { return period_; }
  std::vector<std::uint32_t> sizes() const;
  std::size_t final_index() const { return final_; }
  const std::vector<PermutationHash>& tables() const { return tables_; }

  // thesis eq. (3.5)
  std::uint32_t operator()(std::int64_t x) const;
  // thesis eq. (3.6)
  std::uint32_t operator()(std::int64_t x, std::int64_t y) const;
  // thesis eq. (3.7)
  std::uint32_t operator()(std::int64_t x, std::int64_t y, std::int64_t z) const;

 private:
  std::vector<PermutationHash> tables_;
  std::size_t final_;
  std::uint64_t period_;
};

// A 2-D lattice hash reduced to C colours, in the form the direct tilings evaluate it:
// colour(x, y) = h(x, y) % C with h one permutation table (eq. 3.3, size the smallest
// multiple of C that is >= 256, so that every colour is exactly equally likely) or the
// long-period hash of LongPeriodHash::for_colours (eq. 3.6). row() is the same function
// evaluated along a row, with the per-column lookups P_i[x % N_i] hoisted out of the loop.
class ColourHash {
 public:
  ColourHash(HashKind kind, std::uint32_t colours, std::uint64_t seed);

  HashKind kind() const { return kind_; }
  std::uint32_t colours() const { return colours_; }
  std::uint64_t period() const { return period_; }
  // The period of every lattice row in x: N for one permutation table, else 0 (too long to use).
  std::uint64_t x_period() const { return comps_.size() == 1 ? comps_[0].n : 0; }
  std::uint32_t colour(std::int64_t x, std::int64_t y) const;

  // The permutation tables P_i of size N_i that make up the hash (one for kind Permutation),
  // and the final modulo divisor N_j (the range before the reduction to C colours): what a
  // shader needs to evaluate the same function (render/glsl_sampler.cpp).
  struct Component {
    std::uint32_t n;
    std::vector<std::uint32_t> p;
  };
  const std::vector<Component>& components() const { return comps_; }
  std::uint32_t range() const { return range_; }

  // Per-row evaluation cache for the columns x0, x0 + stride, ..., x0 + (n - 1) stride, with
  // scratch space; one per thread.
  struct RowCache {
    std::int64_t x0 = 0, stride = 1;
    std::size_t n = 0;
    std::vector<std::uint32_t> start, step;  // per component: x0 % N_i and stride % N_i
    std::vector<std::uint16_t> sum;          // the row's sums of component values
    std::vector<std::uint16_t> periodic;     // one component along the row, a whole number of periods
    std::vector<std::uint8_t> bytes;         // row_bytes' output
  };
  void prepare(RowCache& cache, std::int64_t x0, std::size_t n, std::int64_t stride = 1) const;
  // out[k] = colour(x0 + k stride, y) for k < n, with the columns of `cache`. Incremental along
  // the row (thesis eq. 3.3/3.6 per row): component i at column x depends only on x % N_i, and
  // that index advances by the stride mod N_i from one column to the next, so the component is
  // a periodic sequence along the row. Each is evaluated for one block of whole periods and
  // added along the row block by block (vectorised 16-bit adds); the sum is reduced to a colour
  // by multiply-shift division. Equal to colour() at every column (tests/tiling).
  void row(RowCache& cache, std::int64_t y, std::uint16_t* out) const;
  // The same colours as bytes (columns x0 + k, stride 1, k < n; the buffer belongs to the cache),
  // summed in 8 bits, 32 columns per step: only when bytes_suffice(), i.e. every sum of component
  // values is below 256 (the long-period design for C <= 24; one table of 256 entries). The fast
  // corner-tiling kernel (lattice_tiling.hpp) uses it.
  bool bytes_suffice() const { return max_sum_ < 256 && !ext_offset_.empty(); }
  const std::uint8_t* row_bytes(RowCache& cache, std::int64_t y) const;

 private:
  // q = ((s * m) >> 16) >> shift equals s / d for every s <= the largest sum (checked when built).
  struct DivMagic {
    std::uint32_t d = 1, m = 0, shift = 0;
    bool exact = false;
  };
  static DivMagic div_magic(std::uint32_t d, std::uint32_t max_value);
  void row_sums(RowCache& cache, std::int64_t y, std::uint16_t* sum) const;

  HashKind kind_;
  std::uint32_t colours_;
  std::uint32_t range_ = 0;
  std::uint64_t period_ = 0;
  std::vector<Component> comps_;
  static constexpr std::size_t kChunk = 32, kMaxComponents = 8;
  std::uint64_t max_sum_ = 0;  // largest sum of component values
  std::vector<std::uint8_t>
      ext_;  // row_bytes: per component and y % N_i, P_i[(P_i[t % N_i] + y) % N_i] % C, t < N_i + kChunk
  std::vector<std::size_t> ext_offset_;  // where each component's table starts in ext_
  std::vector<std::uint16_t> reduce_;    // sum of component values -> (sum % N_j) % C = sum % C
  DivMagic by_colours_;                  // vectorisable sum % C, when exact for every sum
};

}  // namespace tilekit
