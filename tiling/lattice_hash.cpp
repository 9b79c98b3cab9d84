#include "tiling/lattice_hash.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cstring>
#include <numeric>

#include "base/error.hpp"
#include "base/random.hpp"

namespace tilekit {

HashKind parse_hash_kind(const std::string& name) {
  if (name == "perm") return HashKind::Permutation;
  if (name == "long-period") return HashKind::LongPeriod;
  throw InputError(fmt::format("unknown hash '{}' (expected perm or long-period)", name));
}

const char* hash_kind_name(HashKind k) {
  return k == HashKind::Permutation ? "perm" : "long-period";
}

PermutationHash::PermutationHash(std::uint32_t size, std::uint64_t seed) : n_(size), p_(size), q_(size) {
  if (size < 1) throw InputError("a permutation table needs at least one entry");
  // thesis sec. 3.4.1: start with the identity and exchange the i-th element with a randomly
  // selected one, i = 0..N-2 (Fisher-Yates: j uniform in i..N-1, so every permutation is equally likely).
  SplitMix64 rng(seed);
  for (auto* t : {&p_, &q_}) {
    std::iota(t->begin(), t->end(), 0u);
    for (std::uint32_t i = 0; i + 1 < n_; ++i) std::swap((*t)[i], (*t)[i + rng.below(n_ - i)]);
  }
}

LongPeriodHash::LongPeriodHash(std::vector<std::uint32_t> sizes, std::size_t final_index, std::uint64_t seed)
    : final_(final_index) {
  if (sizes.empty()) throw InputError("a long-period hash needs at least one permutation table");
  if (final_index >= sizes.size()) throw InputError("the final modulo divisor must be one of the table sizes");
  unsigned __int128 lcm = 1;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    tables_.emplace_back(sizes[i], derive_seed(seed, i));
    std::uint64_t l = std::uint64_t(lcm);
    lcm = lcm / std::gcd(l, std::uint64_t(sizes[i])) * sizes[i];
    if (lcm > (unsigned __int128)(1) << 63) throw InputError("long-period hash: period exceeds 2^63");
  }
  period_ = std::uint64_t(lcm);  // thesis sec. 3.4.2.1: lcm of the combining periods
}

LongPeriodHash LongPeriodHash::thesis_tiling_hash(std::uint64_t seed) {
  return LongPeriodHash({24, 17, 19, 23, 29, 31, 37}, 0, seed);
}

LongPeriodHash LongPeriodHash::for_colours(std::uint32_t c, std::uint64_t seed) {
  if (c < 1) throw InputError("a colour hash needs at least one colour");
  const std::uint32_t range = (24 + c - 1) / c * c;
  std::vector<std::uint32_t> sizes = {range};
  auto is_prime = [](std::uint32_t p) {
    for (std::uint32_t d = 2; d * d <= p; ++d)
      if (p % d == 0) return false;
    return p >= 2;
  };
  std::uint32_t candidate = 37;
  for (std::uint32_t p : {17u, 19u, 23u, 29u, 31u, 37u}) {
    if (range % p == 0) {  // keep the sizes pairwise coprime (thesis sec. 3.4.2.4)
      do ++candidate;
      while (!is_prime(candidate) || range % candidate == 0);
      p = candidate;
    }
    sizes.push_back(p);
  }
  return LongPeriodHash(std::move(sizes), 0, seed);
}

std::vector<std::uint32_t> LongPeriodHash::sizes() const {
  std::vector<std::uint32_t> s;
  for (const auto& t : tables_) s.push_back(t.size());
  return s;
}

std::uint32_t LongPeriodHash::operator()(std::int64_t x) const {
  std::uint64_t sum = 0;
  for (const auto& t : tables_) sum += t(x);  // thesis eq. (3.5)
  return std::uint32_t(sum % tables_[final_].size());
}

std::uint32_t LongPeriodHash::operator()(std::int64_t x, std::int64_t y) const {
  std::uint64_t sum = 0;
  for (const auto& t : tables_) sum += t(x, y);  // thesis eq. (3.6)
  return std::uint32_t(sum % tables_[final_].size());
}

std::uint32_t LongPeriodHash::operator()(std::int64_t x, std::int64_t y, std::int64_t z) const {
  std::uint64_t sum = 0;
  for (const auto& t : tables_) sum += t(x, y, z);  // thesis eq. (3.7)
  return std::uint32_t(sum % tables_[final_].size());
}

namespace {

std::uint32_t floor_mod(std::int64_t v, std::uint32_t n) {
  const std::int64_t r = v % std::int64_t(n);
  return std::uint32_t(r < 0 ? r + n : r);
}

}  // namespace

ColourHash::DivMagic ColourHash::div_magic(std::uint32_t d, std::uint32_t max_value) {
  DivMagic g;
  g.d = d;
  if (max_value >= (1u << 16)) return g;
  for (std::uint32_t shift = 0; shift < 16; ++shift) {
    const std::uint64_t m = ((std::uint64_t(1) << (16 + shift)) + d - 1) / d;  // ceil(2^(16+shift) / d)
    if (m >= (1u << 16)) break;
    bool ok = true;
    for (std::uint32_t s = 0; s <= max_value && ok; ++s) ok = ((s * m) >> 16 >> shift) == s / d;
    if (ok) return {d, std::uint32_t(m), shift, true};
  }
  return g;
}

ColourHash::ColourHash(HashKind kind, std::uint32_t colours, std::uint64_t seed) : kind_(kind), colours_(colours) {
  if (colours < 1 || colours > 65535)
    throw InputError(fmt::format("a colour hash needs 1..65535 colours, got {}", colours));
  if (kind == HashKind::Permutation) {
    PermutationHash p((256 + colours - 1) / colours * colours, seed);
    comps_.push_back({p.size(), p.table()});
    range_ = p.size();
    period_ = p.period();
  } else {
    LongPeriodHash h = LongPeriodHash::for_colours(colours, seed);
    for (const auto& t : h.tables()) comps_.push_back({t.size(), t.table()});
    range_ = h.range();
    period_ = h.period();
  }
  // Both designs make the range a multiple of C, so (sum % N_j) % C = sum % C.
  assert(range_ % colours_ == 0);
  for (const auto& c : comps_) max_sum_ += c.n - 1;
  reduce_.resize(max_sum_ + 1);
  for (std::uint64_t s = 0; s <= max_sum_; ++s) reduce_[s] = std::uint16_t((s % range_) % colours);
  by_colours_ = div_magic(colours, std::uint32_t(std::min<std::uint64_t>(max_sum_, 1u << 16)));
  // row_bytes' tables: ext_[i][y % N_i][t] for t < N_i + kChunk, each value already mod C (the sum
  // of the values mod C is the colour, as reduce_ says), so a row's sums stay below m * C.
  if (max_sum_ < 256 && comps_.size() <= kMaxComponents)
    for (const Component& c : comps_) {
      ext_offset_.push_back(ext_.size());
      for (std::uint32_t ym = 0; ym < c.n; ++ym)
        for (std::uint32_t t = 0; t < c.n + kChunk; ++t)
          ext_.push_back(std::uint8_t(c.p[(c.p[t % c.n] + ym) % c.n] % colours));
    }
}

std::uint32_t ColourHash::colour(std::int64_t x, std::int64_t y) const {
  std::uint64_t sum = 0;
  for (const auto& c : comps_)
    sum += c.p[(c.p[floor_mod(x, c.n)] + floor_mod(y, c.n)) % c.n];  // thesis eq. (3.3) / (3.6)
  return reduce_[sum];
}

void ColourHash::prepare(RowCache& cache, std::int64_t x0, std::size_t n, std::int64_t stride) const {
  cache.x0 = x0;
  cache.stride = stride;
  cache.n = n;
  cache.start.resize(comps_.size());
  cache.step.resize(comps_.size());
  for (std::size_t i = 0; i < comps_.size(); ++i) {
    cache.start[i] = floor_mod(x0, comps_[i].n);
    cache.step[i] = floor_mod(stride, comps_[i].n);
  }
}

// sum[k] = sum_i P_i[(P_i[x_k % N_i] + y) % N_i] for the row's columns x_k (16 bits: the caller
// checks that max_sum_ fits). Component i depends on x only through x % N_i, which
// advances by the stride mod N_i from column to column: a periodic sequence, evaluated for one
// block of whole periods (at least 64 columns) and added block by block (vectorised adds).
void ColourHash::row_sums(RowCache& cache, std::int64_t y, std::uint16_t* sum) const {
  const std::size_t n = cache.n;
  for (std::size_t i = 0; i < comps_.size(); ++i) {
    const Component& c = comps_[i];
    const std::uint32_t N = c.n, ym = floor_mod(y, N), st = cache.step[i];
    const std::uint32_t period = N / std::gcd(st == 0 ? N : st, N);
    const std::size_t block = std::min<std::size_t>(n, std::size_t(period) * ((64 + period - 1) / period));
    cache.periodic.resize(block);
    std::uint16_t* per = cache.periodic.data();
    const std::uint32_t* p = c.p.data();
    for (std::uint32_t t = 0, m = cache.start[i]; t < block; ++t) {
      const std::uint32_t s = p[m] + ym;
      per[t] = std::uint16_t(p[s >= N ? s - N : s]);  // thesis eq. (3.3): P[(P[x % N] + y) % N]
      m += st;
      if (m >= N) m -= N;
    }
    for (std::size_t k = 0; k < n; k += block) {
      const std::size_t len = std::min(block, n - k);
      std::uint16_t* dst = sum + k;
      if (i == 0)
        std::copy_n(per, len, dst);
      else
        for (std::size_t t = 0; t < len; ++t) dst[t] = std::uint16_t(dst[t] + per[t]);
    }
  }
}

void ColourHash::row(RowCache& cache, std::int64_t y, std::uint16_t* out) const {
  const std::size_t n = cache.n;
  if (max_sum_ >= (1u << 16)) {  // sums beyond 16 bits (C near 65535): point by point
    for (std::size_t k = 0; k < n; ++k) out[k] = std::uint16_t(colour(cache.x0 + std::int64_t(k) * cache.stride, y));
    return;
  }
  cache.sum.resize(n);
  std::uint16_t* sum = cache.sum.data();
  row_sums(cache, y, sum);
  if (by_colours_.exact) {  // sum % C by multiply-shift (vectorised)
    const std::uint16_t d = std::uint16_t(by_colours_.d), m = std::uint16_t(by_colours_.m);
    const std::uint32_t sh = by_colours_.shift;
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint16_t s = sum[k];
      const std::uint16_t q = std::uint16_t(std::uint16_t((std::uint32_t(s) * std::uint32_t(m)) >> 16) >> sh);
      out[k] = std::uint16_t(s - d * q);
    }
  } else {
    for (std::size_t k = 0; k < n; ++k) out[k] = reduce_[sum[k]];
  }
}

// One pass over the row in chunks of kChunk columns (one AVX2 register of bytes): each component
// adds kChunk consecutive entries of its table row ext_[y % N_i], starting at its index
// x % N_i, which then advances by kChunk mod N_i (the incremental evaluation of thesis eq. 3.6).
TILEKIT_CLONES const std::uint8_t* ColourHash::row_bytes(RowCache& cache, std::int64_t y) const {
  assert(bytes_suffice() && cache.stride == 1 && comps_.size() <= kMaxComponents);
  const std::size_t chunks = (cache.n + kChunk - 1) / kChunk, m = comps_.size();
  cache.bytes.resize(chunks * kChunk);
  const std::uint8_t* base[kMaxComponents];
  std::uint32_t off[kMaxComponents], adv[kMaxComponents], size[kMaxComponents];
  for (std::size_t i = 0; i < m; ++i) {
    size[i] = comps_[i].n;
    base[i] = ext_.data() + ext_offset_[i] + std::size_t(floor_mod(y, size[i])) * (size[i] + kChunk);
    off[i] = cache.start[i];
    adv[i] = kChunk % size[i];
  }
  std::uint8_t* out = cache.bytes.data();
  const std::uint32_t c = colours_;
  const bool power_of_two = (c & (c - 1)) == 0;
  const std::uint8_t mask = std::uint8_t(c - 1);
  // The sums are below m * C (each value is mod C): C 2^j, j descending, subtracted where it fits
  // leaves the sum mod C. In bytes, min(s, s - k) is s - k when s >= k and s otherwise (s - k
  // wraps above s), two vector instructions per step.
  std::uint8_t steps[8];
  std::size_t nsteps = 0;
  const std::uint64_t largest = std::min<std::uint64_t>(std::uint64_t(m) * (c - 1), max_sum_);  // < 256
  for (std::uint64_t k = c; k <= largest; k *= 2) steps[nsteps++] = std::uint8_t(k);
  using Bytes = std::uint8_t __attribute__((vector_size(kChunk)));  // one register (AVX2), two (SSE2)
  for (std::size_t k = 0; k < chunks; ++k) {
    Bytes acc, v;
    std::memcpy(&acc, base[0] + off[0], kChunk);
    for (std::size_t i = 1; i < m; ++i) {
      std::memcpy(&v, base[i] + off[i], kChunk);
      acc += v;
    }
    for (std::size_t i = 0; i < m; ++i) {
      off[i] += adv[i];
      if (off[i] >= size[i]) off[i] -= size[i];
    }
    if (power_of_two) {
      acc &= mask;
    } else {
      for (std::size_t j = nsteps; j-- > 0;) {
        const Bytes less = acc - steps[j];
        acc = acc < less ? acc : less;
      }
    }
    std::memcpy(out + k * kChunk, &acc, kChunk);
  }
  return out;
}

}  // namespace tilekit
