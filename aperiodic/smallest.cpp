#include "aperiodic/smallest.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <stdexcept>
#include <tuple>

#include "aperiodic/recorded_data.hpp"
#include "aperiodic/steps.hpp"
#include "base/error.hpp"
#include "base/json_input.hpp"

namespace tilekit {

namespace {

constexpr std::string_view kRecordFormat = "tilekit-smallest-chain";
constexpr std::string_view kEmbeddedRecord = "smallest-chain.json";

}  // namespace

const std::vector<std::string>& published_aperiodic_sets() {
  static const std::vector<std::string> s = {"culik-13", "kari-14", "ammann-gs-16", "jeandel-rao-11", "labbe-19"};
  return s;
}

nlohmann::json smallest_record(const std::string& command, const EnumerateResult& r) {
  const EnumNode* best = nullptr;
  for (const auto& [h, n] : r.nodes)
    if (n.depth >= 0 && n.kind == TileKind::Corner &&
        (!best || std::tie(n.tiles, n.colours, n.hash) < std::tie(best->tiles, best->colours, best->hash)))
      best = &n;
  if (!best) throw NotFound("the search reached no corner set with a sound chain: nothing to record");
  std::vector<ChainLink> chain = recorded_chain(r, best->hash);
  nlohmann::json steps = nlohmann::json::array();
  for (std::size_t i = 1; i < chain.size(); ++i) steps.push_back(chain[i].step);
  return {{"format", kRecordFormat}, {"command", command},     {"digest", r.digest},     {"complete", r.complete},
          {"expanded", r.expanded},  {"sets", r.nodes.size()}, {"source", best->root},   {"steps", steps},
          {"set", best->hash},       {"tiles", best->tiles},   {"colors", best->colours}};
}

RecordedChain parse_smallest_record(std::string_view text, const std::string& origin) {
  const nlohmann::json doc = parse_json_input(text, origin);
  const JsonIn j(doc, origin);
  if (j.at("format").string() != kRecordFormat)
    throw j.at("format").error(fmt::format("expected \"{}\"", kRecordFormat));
  RecordedChain c;
  c.source = j.at("source").string(256);
  const JsonIn steps = j.at("steps");
  for (std::size_t i = 0, n = steps.array(0, 64); i < n; ++i) c.steps.push_back(steps[i].string(256));
  c.set = j.at("set").string(64);
  c.tiles = j.at("tiles").unsigned_integer();
  c.colours = static_cast<std::uint32_t>(j.at("colors").unsigned_integer(1u << 20));
  c.command = j.at("command").string(4096);
  c.digest = j.at("digest").string(64);
  c.complete = j.at("complete").boolean();
  c.expanded = j.at("expanded").unsigned_integer();
  c.sets = j.at("sets").unsigned_integer();
  return c;
}

RecordedChain embedded_smallest_record() {
  for (const EmbeddedFile& f : recorded_data())
    if (f.name == kEmbeddedRecord) return parse_smallest_record(f.text, "aperiodic/data/smallest-chain.json");
  throw std::logic_error("aperiodic/data/smallest-chain.json is not embedded");
}

CornerSetCandidate rederive_chain(const RecordedChain& record) {
  CornerSetCandidate c;
  c.record = record;
  c.source = record.source;
  std::vector<ReplayedLink> links = replay_chain(record.source, record.steps, &c.set);
  std::set<std::string> labels;
  std::vector<std::string> steps;
  // Link i by the steps that re-derive it: what a user reruns (`aperiodic link`) to see it.
  auto link_name = [&](std::size_t i) {
    if (i == 0) return fmt::format("link 0 (the source {})", record.source);
    if (i == 1) return fmt::format("link 1 (step {} from {})", links[i].step, record.source);
    return fmt::format("link {} (step {} after {})", i, links[i].step,
                       fmt::join(record.steps.begin(), record.steps.begin() + std::ptrdiff_t(i - 1), ","));
  };
  for (std::size_t i = 0; i < links.size(); ++i) {
    const ReplayedLink& l = links[i];
    if (!sound_label(l.label))
      throw InputError(fmt::format("the chain from {}: {} re-derives with the label {}, which is not sound",
                                   record.source, link_name(i), l.label));
    if (i > 0) steps.push_back(l.step), labels.insert(l.label);
    c.chain.push_back({l.step, l.hash, l.tiles, l.colours, std::string(kind_name(l.kind)), l.label, l.argument,
                       LinkDerivation{record.source, steps}});
  }
  const std::size_t last = links.size() - 1;
  if (links.back().hash != record.set)
    throw InputError(fmt::format("the chain from {}: {} re-derives to set {}, not the recorded set {}", record.source,
                                 link_name(last), links.back().hash, record.set));
  if (c.set.kind() != TileKind::Corner)
    throw InputError(fmt::format("the chain from {}: {} re-derives to a Wang set, not a corner set", record.source,
                                 link_name(last)));
  if (c.set.size() != record.tiles || c.set.colours() != record.colours)
    throw InputError(fmt::format("the chain from {}: {} re-derives to {} tiles and {} colours, not the recorded {} and {}",
                                 record.source, link_name(last), c.set.size(), c.set.colours(), record.tiles,
                                 record.colours));
  c.tiles = c.set.size();
  c.colours = c.set.colours();
  c.soundness = fmt::format("{}", fmt::join(labels, "+"));
  return c;
}

CornerSetCandidate smallest_aperiodic_corner_set() { return rederive_chain(embedded_smallest_record()); }

}  // namespace tilekit
