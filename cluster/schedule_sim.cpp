#include "cluster/schedule_sim.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <sstream>
#include <utility>

#include "base/error.hpp"
#include "base/input.hpp"

namespace tilekit::cluster {

const char* policy_name(SchedulePolicy p) {
  switch (p) {
    case SchedulePolicy::Static: return "static";
    case SchedulePolicy::Pool: return "pool";
    case SchedulePolicy::Split: return "split";
    case SchedulePolicy::Steal: return "steal";
  }
  return "?";
}

SchedulePolicy policy_from_name(const std::string& word) {
  for (SchedulePolicy p : {SchedulePolicy::Static, SchedulePolicy::Pool, SchedulePolicy::Split, SchedulePolicy::Steal})
    if (word == policy_name(p)) return p;
  throw InputError(fmt::format("unknown scheduling policy '{}' (static, pool, split or steal)", word));
}

double Trace::work() const {
  double w = 0;
  for (const TraceUnit& u : units) w += u.cost;
  return w;
}

double Trace::largest_piece() const {
  double m = 0;
  for (const TraceUnit& u : units)
    if (u.pieces.empty())
      m = std::max(m, u.cost);
    else
      for (double p : u.pieces) m = std::max(m, p);
  return m;
}

namespace {

double number(const nlohmann::json& j, const char* key, const std::string& where) {
  if (!j.contains(key) || !j[key].is_number() || !(j[key].get<double>() >= 0))
    throw InputError(fmt::format("{}: `{}` must be a number >= 0", where, key));
  return j[key].get<double>();
}

}  // namespace

Trace read_trace(const std::vector<std::string>& files, const std::string& cost) {
  if (cost != "nodes" && cost != "seconds")
    throw InputError(fmt::format("unknown cost '{}' (nodes or seconds)", cost));
  if (files.empty()) throw InputError("no trace file given");
  const bool by_nodes = cost == "nodes";
  Trace t;
  std::map<std::uint64_t, TraceUnit> by_index;  // exhaustive runs: one unit per subproblem index
  bool saw_count = false;
  std::string count_title;  // an exhaustive trace is one search (its ranks or shards)
  for (const std::string& file : files) {
    t.files += (t.files.empty() ? "" : " ") + file;
    std::istringstream in(read_input_file(file, "trace"));
    std::string line;
    for (std::size_t n = 1; std::getline(in, line); ++n) {
      if (line.empty()) continue;
      const std::string where = fmt::format("{} line {}", file, n);
      nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
      if (!j.is_object() || !j.contains("type") || !j["type"].is_string())
        throw InputError(fmt::format("{}: not a trace line (a JSON object with a \"type\")", where));
      const std::string type = j["type"].get<std::string>();
      if (type == "search") {
        const bool first = j.value("mode", std::string("count")) == "first";
        (first ? t.first : saw_count) = true;
        const std::string title = j.value("title", std::string());
        if (!first && !count_title.empty() && title != count_title)
          throw InputError(fmt::format("{}: the search \"{}\" is not the trace's \"{}\" (one run per simulation)", where,
                                       title, count_title));
        if (!first) count_title = title;
        continue;
      }
      if (type != "subproblem" && type != "dive") continue;  // later kinds of line: not work units
      TraceUnit u;
      u.index = std::uint64_t(number(j, type == "dive" ? "dive" : "index", where));
      u.cost = number(j, by_nodes ? "nodes" : "seconds", where);
      if (j.contains("pieces")) {
        if (!j["pieces"].is_array()) throw InputError(fmt::format("{}: `pieces` must be an array", where));
        double sum = 0;
        for (const auto& p : j["pieces"]) {
          if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number() || !(p[0].get<double>() >= 0) ||
              !(p[1].get<double>() >= 0))
            throw InputError(fmt::format("{}: a piece must be [nodes, seconds] >= 0", where));
          u.pieces.push_back(p[by_nodes ? 0 : 1].get<double>());
          sum += u.pieces.back();
        }
        if (!u.pieces.empty()) u.cost = sum;
      }
      u.found = type == "dive" ? j.value("found", false) : j.value("solutions", 0.0) > 0;
      if (type == "dive" || t.first) {
        t.units.push_back(std::move(u));
      } else {
        by_index.emplace(u.index, std::move(u));  // a subproblem run again after a resume: the first
      }
    }
  }
  if (t.first && saw_count) throw InputError(fmt::format("{}: a first-mode and an exhaustive run in one trace", t.files));
  if (!t.first) {
    for (auto& [i, u] : by_index) t.units.push_back(std::move(u));
  } else {  // the run ended with the unit that found
    auto f = std::find_if(t.units.begin(), t.units.end(), [](const TraceUnit& u) { return u.found; });
    if (f != t.units.end()) {
      t.units.erase(f + 1, t.units.end());
      t.found = true;
    }
  }
  if (!(t.work() > 0)) throw InputError(fmt::format("{}: the trace holds no work (no subproblem or dive with a cost)", t.files));
  return t;
}

namespace {

using Pieces = std::deque<double>;

Pieces pieces_of(const TraceUnit& u) {
  if (u.pieces.empty()) return {u.cost};
  return Pieces(u.pieces.begin(), u.pieces.end());
}

// Whole units in order on the first free worker; the end of unit `stop_at` (or of all).
double list_schedule(const std::vector<double>& costs, std::int64_t workers, std::size_t stop_at) {
  std::priority_queue<double, std::vector<double>, std::greater<>> free;
  for (std::int64_t w = 0; w < workers && w < std::int64_t(costs.size()); ++w) free.push(0);
  double end = 0;
  for (std::size_t i = 0; i < costs.size(); ++i) {
    const double t = free.top() + costs[i];
    free.pop();
    free.push(t);
    end = std::max(end, t);
    if (i == stop_at) return t;
  }
  return end;
}

double static_schedule(const Trace& tr, std::int64_t P) {
  std::vector<double> load(std::size_t(std::min<std::int64_t>(P, std::int64_t(tr.units.size()) + 1)), 0.0);
  const std::size_t found = tr.found ? tr.units.size() - 1 : tr.units.size();
  for (std::size_t k = 0; k < tr.units.size(); ++k) {
    // exhaustive: the engine's rule, subproblem index mod P; first mode: the k-th unit run
    const std::uint64_t key = tr.first ? k : tr.units[k].index;
    const std::size_t w = std::size_t(key % std::uint64_t(P));
    if (w >= load.size()) load.resize(w + 1, 0.0);
    load[w] += tr.units[k].cost;
    if (k == found) return load[w];
  }
  return *std::max_element(load.begin(), load.end());
}

// Rounds of static arrays, each cut at its fair share; the outstanding work of a cut shard
// becomes new units (unstarted subproblems whole, the running one's pieces one each).
double split_schedule(const Trace& tr, std::int64_t P, int max_rounds, int& rounds) {
  std::vector<Pieces> items;
  for (const TraceUnit& u : tr.units) items.push_back(pieces_of(u));
  double makespan = 0;
  rounds = 0;
  while (!items.empty()) {
    ++rounds;
    double outstanding = 0;
    for (const Pieces& it : items)
      for (double p : it) outstanding += p;
    const bool last = rounds >= max_rounds;
    const double budget = last ? std::numeric_limits<double>::infinity() : outstanding / double(P);
    std::vector<std::vector<std::size_t>> mine(std::size_t(std::min<std::int64_t>(P, std::int64_t(items.size()))));
    for (std::size_t k = 0; k < items.size(); ++k) mine[k % mine.size()].push_back(k);
    std::vector<Pieces> next;
    double length = 0;
    for (const auto& list : mine) {
      double t = 0;
      bool cut = false;
      for (std::size_t k : list) {
        Pieces& it = items[k];
        if (cut) {  // not started: stays whole
          next.push_back(std::move(it));
          continue;
        }
        while (!it.empty()) {
          if (t + it.front() <= budget) {
            t += it.front();
            it.pop_front();
            continue;
          }
          // the shard's share is used up inside this piece: its rest and every unstarted piece
          // become units of their own
          const double rest = it.front() - (budget - t);
          it.pop_front();
          t = budget;
          next.push_back({rest});
          for (double p : it) next.push_back({p});
          it.clear();
          cut = true;
        }
      }
      length = std::max(length, t);
    }
    makespan += length;
    items = std::move(next);
  }
  return makespan;
}

// Dynamic pool, then steals of the later half of the busiest worker's unstarted pieces.
double steal_schedule(const Trace& tr, std::int64_t P, std::uint64_t& steals) {
  std::int64_t pieces = 0;  // more workers than pieces would only idle
  for (const TraceUnit& u : tr.units) pieces += std::int64_t(std::max<std::size_t>(1, u.pieces.size()));
  const std::size_t W = std::size_t(std::min(P, pieces));
  std::vector<Pieces> dq(W);
  std::vector<double> stealable(W, 0.0);
  std::vector<std::uint64_t> version(W, 0);
  std::priority_queue<std::tuple<double, std::size_t, std::uint64_t>> victims;  // (unstarted work, worker, version)
  auto update = [&](std::size_t w) {
    ++version[w];
    if (dq[w].size() > 0 && stealable[w] > 0) victims.emplace(stealable[w], w, version[w]);
  };
  using Event = std::pair<double, std::size_t>;  // (time the worker is free, worker)
  std::priority_queue<Event, std::vector<Event>, std::greater<>> events;
  for (std::size_t w = 0; w < W; ++w) events.emplace(0.0, w);
  std::size_t next_unit = 0;
  double makespan = 0;
  while (!events.empty()) {
    auto [now, w] = events.top();
    events.pop();
    makespan = std::max(makespan, now);
    if (dq[w].empty() && next_unit < tr.units.size()) {
      dq[w] = pieces_of(tr.units[next_unit++]);
      stealable[w] = 0;
      for (double p : dq[w]) stealable[w] += p;
    }
    if (dq[w].empty()) {  // steal from the worker with the most unstarted work
      while (!victims.empty()) {
        auto [amount, v, ver] = victims.top();
        if (ver != version[v] || v == w || dq[v].empty()) {
          victims.pop();
          continue;
        }
        victims.pop();
        const std::size_t take = (dq[v].size() + 1) / 2;
        for (std::size_t i = dq[v].size() - take; i < dq[v].size(); ++i) dq[w].push_back(dq[v][i]);
        dq[v].resize(dq[v].size() - take);
        stealable[v] = 0;
        for (double p : dq[v]) stealable[v] += p;
        stealable[w] = 0;
        for (double p : dq[w]) stealable[w] += p;
        update(v);
        ++steals;
        break;
      }
    }
    if (dq[w].empty()) continue;  // nothing left anywhere that is not running: this worker is done
    const double piece = dq[w].front();
    dq[w].pop_front();
    stealable[w] -= piece;
    if (dq[w].empty()) stealable[w] = 0;
    update(w);
    events.emplace(now + piece, w);
  }
  return makespan;
}

}  // namespace

SimResult simulate(const Trace& tr, SchedulePolicy policy, std::int64_t workers, int max_rounds) {
  if (workers < 1) throw InputError(fmt::format("`workers` must be at least 1, got {}", workers));
  if (max_rounds < 1) throw InputError(fmt::format("`rounds` must be at least 1, got {}", max_rounds));
  if (tr.units.empty()) throw InputError("the trace holds no work");
  SimResult r;
  r.policy = policy;
  r.workers = workers;
  r.ideal = tr.work() / double(workers);
  r.bound = std::max(r.ideal, tr.found ? tr.units.back().cost : tr.largest_piece());
  std::vector<double> costs;
  for (const TraceUnit& u : tr.units) costs.push_back(u.cost);
  const std::size_t stop_at = tr.found ? tr.units.size() - 1 : tr.units.size();
  if (policy == SchedulePolicy::Static) {
    r.makespan = static_schedule(tr, workers);
  } else if (tr.first || policy == SchedulePolicy::Pool) {  // first mode: whole units only
    r.makespan = list_schedule(costs, workers, stop_at);
  } else if (policy == SchedulePolicy::Split) {
    r.makespan = split_schedule(tr, workers, max_rounds, r.rounds);
  } else {
    r.makespan = steal_schedule(tr, workers, r.steals);
  }
  r.efficiency = r.makespan > 0 ? r.ideal / r.makespan : 1.0;
  return r;
}

nlohmann::json to_json(const SimResult& r) {
  return {{"policy", policy_name(r.policy)}, {"workers", r.workers},       {"makespan", r.makespan},
          {"ideal", r.ideal},                {"bound", r.bound},           {"efficiency", r.efficiency},
          {"rounds", r.rounds},              {"steals", r.steals}};
}

}  // namespace tilekit::cluster
