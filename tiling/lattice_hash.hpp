#pragma once
// Hash functions over the integer lattice (thesis sec. 3.4): traditional hashes based on one
// permutation table (eq. 3.1-3.4) and long-period combined hashes (eq. 3.5-3.7), plus
// ColourHash, the lattice hash reduced to C colours that the direct stochastic tiling
// algorithms use (thesis sec. 3.4.3). Coordinates are 64-bit; x % N is the floored modulo,
// so every hash is periodic over all of Z (negative coordinates included).
#include <cstdint>
#include <string>
#include <vector>

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

  // Per-row evaluation cache: the columns x0..x0+n-1 it was prepared for.
  struct RowCache {
    std::int64_t x0 = 0;
    std::size_t n = 0;
    std::vector<std::uint32_t> first;  // M*n values P_i[x % N_i], component-major
    std::vector<std::uint32_t> sum;    // scratch
  };
  // Columns x0, x0 + stride, ..., x0 + (n - 1) stride.
  void prepare(RowCache& cache, std::int64_t x0, std::size_t n, std::int64_t stride = 1) const;
  // out[k] = colour(x0 + k stride, y) for k < n, with the columns of `cache`.
  void row(RowCache& cache, std::int64_t y, std::uint16_t* out) const;

 private:
  struct Component {
    std::uint32_t n;
    std::vector<std::uint32_t> p;
  };
  HashKind kind_;
  std::uint32_t colours_;
  std::uint64_t period_ = 0;
  std::vector<Component> comps_;
  std::vector<std::uint16_t> reduce_;           // sum of component values -> (sum % N_j) % C
  std::vector<std::uint16_t> colour_of_entry_;  // one table: s -> P[s] % C
};

}  // namespace tilekit
