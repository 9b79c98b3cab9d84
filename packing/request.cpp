// PackRequest as JSON, and the request a checkpoint describes (request.hpp).
#include "packing/request.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "base/error.hpp"
#include "base/parse.hpp"

namespace tilekit {
namespace {

// One row per identity field: the field, its JSON key, and how to read and write it.
struct Field {
  PackField field;
  const char* key;
  nlohmann::json (*get)(const PackRequest&);
  void (*set)(PackRequest&, const nlohmann::json&);
};

#define TILEKIT_FIELD(FIELD, KEY, MEMBER, TYPE)                                   \
  Field {                                                                         \
    FIELD, KEY, [](const PackRequest& r) { return nlohmann::json(r.MEMBER); },    \
        [](PackRequest& r, const nlohmann::json& j) { r.MEMBER = j.get<TYPE>(); } \
  }

const Field kFields[] = {
    TILEKIT_FIELD(PackField::Kind, "kind", kind, std::string),
    TILEKIT_FIELD(PackField::Colours, "colors", colours, std::int64_t),
    TILEKIT_FIELD(PackField::Window, "window", window, std::string),
    TILEKIT_FIELD(PackField::Set, "set", set, std::string),
    TILEKIT_FIELD(PackField::Size, "size", size, std::string),
    TILEKIT_FIELD(PackField::Method, "method", method, std::string),
    TILEKIT_FIELD(PackField::Mode, "mode", mode, std::string),
    // Stored as its word ("auto", "cell", ...).
    Field{PackField::Formulation, "formulation",
          [](const PackRequest& r) { return nlohmann::json(std::string(formulation_name(r.formulation))); },
          [](PackRequest& r, const nlohmann::json& j) {
            const std::optional<Formulation> f = formulation_from_name(j.get<std::string>());
            if (!f) throw InputError("unknown formulation");
            r.formulation = *f;
          }},
    TILEKIT_FIELD(PackField::Ordering, "ordering", ordering, std::string),
    TILEKIT_FIELD(PackField::Impose, "impose", impose, std::string),
    TILEKIT_FIELD(PackField::Lift, "lift", lift, std::string),
    TILEKIT_FIELD(PackField::Plain, "plain", plain, bool),
    TILEKIT_FIELD(PackField::Candidates, "candidates", candidates, std::vector<std::string>),
    TILEKIT_FIELD(PackField::Subproblems, "subproblems", subproblems, std::int64_t),
    TILEKIT_FIELD(PackField::Seed, "seed", run.seed, std::uint64_t),
    // Stored as the text "I/N", as every checkpoint has it.
    Field{PackField::Shard, "shard", [](const PackRequest& r) { return nlohmann::json(shard_text(r.run.shard)); },
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

const std::vector<PackField>& pack_fields() {
  static const std::vector<PackField> fields = [] {
    std::vector<PackField> v;
    for (const Field& f : kFields) v.push_back(f.field);
    v.push_back(PackField::TimeLimit);
    return v;
  }();
  return fields;
}

std::string_view pack_field_name(PackField f) {
  switch (f) {
    case PackField::Kind:
      return "kind";
    case PackField::Colours:
      return "colours";
    case PackField::Window:
      return "window";
    case PackField::Set:
      return "set";
    case PackField::Size:
      return "size";
    case PackField::Method:
      return "method";
    case PackField::Mode:
      return "mode";
    case PackField::Formulation:
      return "formulation";
    case PackField::Ordering:
      return "ordering";
    case PackField::Impose:
      return "impose";
    case PackField::Lift:
      return "lift";
    case PackField::Plain:
      return "plain";
    case PackField::Candidates:
      return "candidates";
    case PackField::Subproblems:
      return "subproblems";
    case PackField::Seed:
      return "seed";
    case PackField::Shard:
      return "shard";
    case PackField::TimeLimit:
      return "time_limit";
  }
  return "?";
}

PackRequest resume_request(const PackRequest& here, const PackFields& given, const nlohmann::json& stored,
                           const std::string& checkpoint) {
  PackRequest r = here;
  if (!stored.is_object()) return r;  // a version-1 checkpoint: the flags say it all
  for (const Field& f : kFields) {
    if (!stored.contains(f.key)) continue;
    const nlohmann::json& theirs = stored.at(f.key);
    if (given.count(f.field)) {
      const nlohmann::json mine = f.get(here);
      const std::string name(pack_field_name(f.field));
      if (mine != theirs)
        throw RequestError(
            name, fmt::format("`{}` is {} here but {} in the checkpoint {} (drop it to continue that run)", name,
                              mine.dump(), theirs.dump(), checkpoint));
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
  // The time limit the run was started with, unless it is given again.
  if (!given.count(PackField::TimeLimit) && stored.contains("time_limit")) {
    const nlohmann::json& t = stored["time_limit"];
    if (!t.is_number() || !(t.get<double>() >= 0) || !std::isfinite(t.get<double>()))
      throw InputError(fmt::format("checkpoint {}: the request's time_limit is malformed", checkpoint));
    r.run.time_limit = t.get<double>();
  }
  return r;
}

}  // namespace tilekit
