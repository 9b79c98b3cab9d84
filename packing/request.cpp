// PackRequest as JSON, and the request a checkpoint describes (request.hpp).
#include "packing/request.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "base/error.hpp"
#include "base/parse.hpp"

namespace tilekit {
namespace {

// One row per identity field: its flag, its JSON key, and how to read and write it.
struct Field {
  const char* flag;
  const char* key;
  nlohmann::json (*get)(const PackRequest&);
  void (*set)(PackRequest&, const nlohmann::json&);
};

#define TILEKIT_FIELD(FLAG, KEY, MEMBER, TYPE)                                    \
  Field {                                                                         \
    FLAG, KEY, [](const PackRequest& r) { return nlohmann::json(r.MEMBER); },     \
        [](PackRequest& r, const nlohmann::json& j) { r.MEMBER = j.get<TYPE>(); } \
  }

const Field kFields[] = {
    TILEKIT_FIELD("--kind", "kind", kind, std::string),
    TILEKIT_FIELD("--colors", "colors", colours, std::int64_t),
    TILEKIT_FIELD("--set", "set", set, std::string),
    TILEKIT_FIELD("--size", "size", size, std::string),
    TILEKIT_FIELD("--method", "method", method, std::string),
    TILEKIT_FIELD("--mode", "mode", mode, std::string),
    TILEKIT_FIELD("--formulation", "formulation", formulation, std::string),
    TILEKIT_FIELD("--ordering", "ordering", ordering, std::string),
    TILEKIT_FIELD("--impose", "impose", impose, std::string),
    TILEKIT_FIELD("--lift", "lift", lift, std::string),
    TILEKIT_FIELD("--plain", "plain", plain, bool),
    TILEKIT_FIELD("--candidate", "candidates", candidates, std::vector<std::string>),
    TILEKIT_FIELD("--seed", "seed", run.seed, std::uint64_t),
    // Stored as the flag's text "I/N", as every checkpoint has it.
    Field{"--shard", "shard", [](const PackRequest& r) { return nlohmann::json(shard_text(r.run.shard)); },
          [](PackRequest& r, const nlohmann::json& j) { r.run.shard = parse_shard(j.get<std::string>()); }},
};

#undef TILEKIT_FIELD

}  // namespace

nlohmann::json request_identity(const PackRequest& r) {
  nlohmann::json j = nlohmann::json::object();
  for (const Field& f : kFields) j[f.key] = f.get(r);
  std::error_code ec;
  if (!r.db.empty()) j["db"] = std::filesystem::absolute(r.db, ec).string();
  return j;
}

const std::vector<std::string>& identity_flags() {
  static const std::vector<std::string> flags = [] {
    std::vector<std::string> v;
    for (const Field& f : kFields) v.push_back(f.flag);
    return v;
  }();
  return flags;
}

PackRequest resume_request(const PackRequest& here, const std::set<std::string>& given, const nlohmann::json& stored,
                           const std::string& checkpoint) {
  PackRequest r = here;
  if (!stored.is_object()) return r;  // a version-1 checkpoint: the flags say it all
  for (const Field& f : kFields) {
    if (!stored.contains(f.key)) continue;
    const nlohmann::json& theirs = stored.at(f.key);
    if (given.count(f.flag)) {
      const nlohmann::json mine = f.get(here);
      if (mine != theirs)
        throw InputError(fmt::format("{} is {} here but {} in the checkpoint {} (drop the flag to continue that run)",
                                     f.flag, mine.dump(), theirs.dump(), checkpoint));
      continue;
    }
    try {
      f.set(r, theirs);
    } catch (const nlohmann::json::exception&) {
      throw InputError(fmt::format("checkpoint {}: the request's {} is malformed", checkpoint, f.key));
    } catch (const InputError&) {
      throw InputError(fmt::format("checkpoint {}: the request's {} is malformed", checkpoint, f.key));
    }
  }
  if (here.db.empty() && stored.contains("db") && stored["db"].is_string()) r.db = stored["db"].get<std::string>();
  return r;
}

}  // namespace tilekit
