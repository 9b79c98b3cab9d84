#include "tiling/lattice_hash.hpp"

#include <fmt/format.h>

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

ColourHash::ColourHash(HashKind kind, std::uint32_t colours, std::uint64_t seed) : kind_(kind), colours_(colours) {
  if (colours < 1 || colours > 65535)
    throw InputError(fmt::format("a colour hash needs 1..65535 colours, got {}", colours));
  std::uint32_t final_size = 0;
  if (kind == HashKind::Permutation) {
    PermutationHash p((256 + colours - 1) / colours * colours, seed);
    comps_.push_back({p.size(), p.table()});
    final_size = p.size();
    period_ = p.period();
  } else {
    LongPeriodHash h = LongPeriodHash::for_colours(colours, seed);
    for (const auto& t : h.tables()) comps_.push_back({t.size(), t.table()});
    final_size = h.range();
    period_ = h.period();
  }
  std::uint64_t max_sum = 0;
  for (const auto& c : comps_) max_sum += c.n - 1;
  reduce_.resize(max_sum + 1);
  for (std::uint64_t s = 0; s <= max_sum; ++s) reduce_[s] = std::uint16_t((s % final_size) % colours);
  if (comps_.size() == 1)
    for (std::uint32_t v : comps_[0].p) colour_of_entry_.push_back(reduce_[v]);
}

std::uint32_t ColourHash::colour(std::int64_t x, std::int64_t y) const {
  std::uint64_t sum = 0;
  for (const auto& c : comps_) {
    auto mod = [&](std::int64_t v) {
      std::int64_t r = v % std::int64_t(c.n);
      return std::uint64_t(r < 0 ? r + c.n : r);
    };
    sum += c.p[(c.p[mod(x)] + mod(y)) % c.n];  // thesis eq. (3.3) / (3.6)
  }
  return reduce_[sum];
}

void ColourHash::prepare(RowCache& cache, std::int64_t x0, std::size_t n, std::int64_t stride) const {
  cache.x0 = x0;
  cache.n = n;
  cache.first.resize(comps_.size() * n);
  for (std::size_t i = 0; i < comps_.size(); ++i) {
    const Component& c = comps_[i];
    std::int64_t r = x0 % std::int64_t(c.n);
    std::uint32_t m = std::uint32_t(r < 0 ? r + c.n : r);
    std::int64_t step = stride % std::int64_t(c.n);
    const std::uint32_t st = std::uint32_t(step < 0 ? step + c.n : step);
    for (std::size_t k = 0; k < n; ++k) {
      cache.first[i * n + k] = c.p[m];
      m += st;
      if (m >= c.n) m -= c.n;
    }
  }
}

void ColourHash::row(RowCache& cache, std::int64_t y, std::uint16_t* out) const {
  const std::size_t n = cache.n;
  if (comps_.size() == 1) {  // one permutation table: colour = (P[(P[x] + y) % N]) % C
    const Component& c = comps_[0];
    std::int64_t r = y % std::int64_t(c.n);
    const std::uint32_t ym = std::uint32_t(r < 0 ? r + c.n : r);
    const std::uint32_t* first = cache.first.data();
    const std::uint16_t* colour = colour_of_entry_.data();
    for (std::size_t k = 0; k < n; ++k) {
      std::uint32_t s = first[k] + ym;
      s = s >= c.n ? s - c.n : s;
      out[k] = colour[s];
    }
    return;
  }
  std::vector<std::uint32_t>& sum = cache.sum;
  sum.assign(n, 0);
  for (std::size_t i = 0; i < comps_.size(); ++i) {
    const Component& c = comps_[i];
    std::int64_t r = y % std::int64_t(c.n);
    const std::uint32_t ym = std::uint32_t(r < 0 ? r + c.n : r);
    const std::uint32_t* first = cache.first.data() + i * n;
    const std::uint32_t* p = c.p.data();
    for (std::size_t k = 0; k < n; ++k) {
      std::uint32_t s = first[k] + ym;
      sum[k] += p[s >= c.n ? s - c.n : s];
    }
  }
  for (std::size_t k = 0; k < n; ++k) out[k] = reduce_[sum[k]];
}

}  // namespace tilekit
