#include "aperiodic/decide_checkpoint.hpp"

#include <fmt/format.h>

#include <bit>
#include <cerrno>
#include <cstring>
#include <nlohmann/json.hpp>
#include <set>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/input.hpp"
#include "checkpoints/checkpoint.hpp"

namespace tilekit {

namespace {

constexpr std::string_view kMagic = "TILEKIT-DECIDE";

class Writer {
 public:
  void u(std::uint64_t v, int bytes = 8) {
    for (int i = 0; i < bytes; ++i) out_.push_back(char((v >> (8 * i)) & 0xff));
  }
  void f(double v) { u(std::bit_cast<std::uint64_t>(v)); }
  void s(std::string_view v) {
    u(v.size());
    out_.append(v);
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(std::string_view in) : in_(in) {}
  std::uint64_t u(int bytes = 8) {
    need(std::size_t(bytes));
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= std::uint64_t(static_cast<unsigned char>(in_[pos_ + std::size_t(i)])) << (8 * i);
    pos_ += std::size_t(bytes);
    return v;
  }
  std::uint32_t u32() { return std::uint32_t(u(4)); }
  double f() { return std::bit_cast<double>(u()); }
  std::string s() {
    std::size_t n = count(1);
    std::string v(in_.substr(pos_, n));
    pos_ += n;
    return v;
  }
  // A count of items of `size` bytes each that must fit in what is left (no huge allocations).
  std::size_t count(std::size_t size) {
    std::uint64_t n = u();
    if (n > (in_.size() - pos_) / size) throw std::runtime_error("a count runs past the end");
    return std::size_t(n);
  }
  bool done() const { return pos_ == in_.size(); }

 private:
  void need(std::size_t n) {
    if (in_.size() - pos_ < n) throw std::runtime_error("the body ends early");
  }
  std::string_view in_;
  std::size_t pos_ = 0;
};

void write_level(Writer& w, const ChainLevel& l) {
  w.u(l.t.states, 4);
  w.u(l.t.transitions.size());
  for (const Transition& t : l.t.transitions) w.u(t.from, 4), w.u(t.in, 4), w.u(t.out, 4), w.u(t.to, 4);
  w.u(l.keys.size());
  for (std::size_t i = 0; i < l.keys.size(); ++i) w.u(l.keys[i]), w.u(l.cls[i], 4);
  w.u(l.components), w.u(l.product_states), w.u(l.product_transitions);
  w.f(l.seconds);
}

ChainLevel read_level(Reader& r) {
  ChainLevel l;
  l.t.states = r.u32();
  l.t.transitions.resize(r.count(16));
  for (Transition& t : l.t.transitions) t.from = r.u32(), t.in = r.u32(), t.out = r.u32(), t.to = r.u32();
  std::size_t n = r.count(12);
  l.keys.resize(n);
  l.cls.resize(n);
  for (std::size_t i = 0; i < n; ++i) l.keys[i] = r.u(), l.cls[i] = r.u32();
  l.components = r.u(), l.product_states = r.u(), l.product_transitions = r.u();
  l.seconds = r.f();
  return l;
}

}  // namespace

std::string decide_fingerprint(const std::vector<WangTile>& tiles, const DecideOptions& opts) {
  StableHash h;
  for (const WangTile& t : tiles) h.add(t.n, 4).add(t.e, 4).add(t.s, 4).add(t.w, 4);
  return nlohmann::json{{"tiles", tiles.size()},
                        {"tiles_hash", fmt::format("{:016x}", h.mixed())},
                        {"merge", opts.merge},
                        {"rows", opts.rows},
                        {"columns", opts.columns}}
      .dump();
}

std::string encode_decide_checkpoint(const DecideCheckpoint& c) {
  Writer w;
  w.s(c.fingerprint);
  w.f(c.seconds);
  w.u(c.levels.size());
  for (const DecideLevel& l : c.levels) {
    w.u(std::uint64_t(l.k), 4);
    w.u(l.direction == "columns", 1);
    w.u(l.product_states), w.u(l.product_transitions), w.u(l.components), w.u(l.states), w.u(l.transitions);
    w.f(l.seconds);
  }
  w.u(c.chains.size());
  for (const TransducerChain& ch : c.chains) {
    w.u(ch.columns(), 1);
    w.u(ch.merge(), 1);
    w.u(ch.levels().size());
    for (const ChainLevel& l : ch.levels()) write_level(w, l);
  }
  return seal_checkpoint(kMagic, kDecideCheckpointVersion, w.take());
}

namespace {

// The statistics a run reports are those of its chains' own levels, each listed once: a
// checkpoint whose statistics say otherwise (a level of another k or direction, other sizes)
// would resume to a report the tiles do not give.
void check_level_statistics(const DecideCheckpoint& c) {
  std::size_t total = 0;
  for (const TransducerChain& ch : c.chains) total += ch.levels().size();
  if (c.levels.size() != total)
    throw std::runtime_error(fmt::format("{} level statistics for {} chain levels", c.levels.size(), total));
  std::set<std::pair<bool, int>> seen;
  for (const DecideLevel& l : c.levels) {
    const bool columns = l.direction == "columns";
    const TransducerChain* ch = nullptr;
    for (const TransducerChain& x : c.chains)
      if (x.columns() == columns) ch = &x;
    if (!ch || l.k < 1 || std::size_t(l.k) > ch->levels().size() || !seen.insert({columns, l.k}).second)
      throw std::runtime_error(fmt::format("the statistics of level {} ({}) belong to no chain level, or are listed "
                                           "twice",
                                           l.k, l.direction));
    const ChainLevel& cl = ch->level(l.k);
    if (cl.product_states != l.product_states || cl.product_transitions != l.product_transitions ||
        cl.components != l.components || cl.t.states != l.states || cl.t.transitions.size() != l.transitions)
      throw std::runtime_error(
          fmt::format("the statistics of level {} ({}) differ from the level itself", l.k, l.direction));
  }
}

}  // namespace

DecideCheckpoint decode_decide_checkpoint(std::string_view text, const std::vector<WangTile>& tiles,
                                          const std::string& origin) {
  std::string_view body = open_checkpoint(text, kMagic, kDecideCheckpointVersion, kDecideCheckpointVersion, origin);
  DecideCheckpoint c;
  try {
    Reader r(body);
    c.fingerprint = r.s();
    c.seconds = r.f();
    c.levels.resize(r.count(53));
    for (DecideLevel& l : c.levels) {
      l.k = int(r.u32());
      l.direction = r.u(1) ? "columns" : "rows";
      l.product_states = r.u(), l.product_transitions = r.u(), l.components = r.u(), l.states = r.u(), l.transitions = r.u();
      l.seconds = r.f();
    }
    std::size_t chains = r.count(10);
    if (chains == 0 || chains > 2) throw std::runtime_error("a run has one or two chains");
    for (std::size_t i = 0; i < chains; ++i) {
      bool columns = r.u(1) != 0, merge = r.u(1) != 0;
      std::vector<ChainLevel> levels(r.count(1));
      for (ChainLevel& l : levels) l = read_level(r);
      c.chains.push_back(TransducerChain::restore(tiles, columns, merge, std::move(levels)));
    }
    if (!r.done()) throw std::runtime_error("bytes after the last chain");
    check_level_statistics(c);
  } catch (const InputError& e) {
    throw InputError(fmt::format("checkpoint {}: {}", origin, e.what()));
  } catch (const std::exception& e) {
    throw InputError(fmt::format("checkpoint {}: corrupt body ({})", origin, e.what()));
  }
  return c;
}

void write_decide_checkpoint(const std::string& path, const DecideCheckpoint& c) {
  write_file_atomic(path, encode_decide_checkpoint(c));  // sealed in the envelope by the encoder
}

DecideCheckpoint read_decide_checkpoint(const std::string& path, const std::vector<WangTile>& tiles) {
  // A regular file of at most kMaxCheckpointBytes; the envelope is checked as it is decoded.
  return decode_decide_checkpoint(read_input_file(path, "checkpoint", kMaxCheckpointBytes), tiles, path);
}

}  // namespace tilekit
