// tilekit aperiodic certify: the certificate of a recorded chain (aperiodic/certify.hpp), checked
// by the independent checker before it is written. tilekit aperiodic check-certificate: that
// checker (certificate/check.hpp) on a file, against the built-in copy of the source set.
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "aperiodic/certify.hpp"
#include "aperiodic/smallest.hpp"
#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/input.hpp"
#include "base/json_input.hpp"
#include "certificate/check.hpp"
#include "cli/cmd_aperiodic.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit::cli {

namespace {

constexpr std::size_t kMaxCertificateBytes = std::size_t(512) << 20;

std::vector<certificate::Tile> reference_tiles(const std::string& name) {
  std::vector<certificate::Tile> out;
  const TileSet s = resolve_tile_set(name);
  if (s.kind() != TileKind::Wang) return out;
  for (const WangTile& t : s.wang_tiles()) out.push_back({t.n, t.e, t.s, t.w});
  return out;
}

// The source's built-in copy, by the certificate's source name (InputError: not a built-in set).
std::vector<certificate::Tile> reference_for(const nlohmann::json& cert, const std::string& origin) {
  if (!cert.is_object() || !cert.contains("source") || !cert["source"].is_object() ||
      !cert["source"].contains("name") || !cert["source"]["name"].is_string())
    throw InputError(fmt::format("{}: not a certificate (no source name)", origin));
  const std::string name = cert["source"]["name"].get<std::string>();
  const auto& known = published_enumeration_sources();
  if (std::find(known.begin(), known.end(), name) == known.end())
    throw InputError(fmt::format("{}: source '{}' is not a published set (expected one of: {})", origin, name,
                                 fmt::join(known, ", ")));
  return reference_tiles(name);
}

nlohmann::json report_json(const certificate::Report& r) {
  nlohmann::json links = nlohmann::json::array();
  for (const auto& l : r.links)
    links.push_back({{"op", l.op}, {"from_tiles", l.from_tiles}, {"to_tiles", l.to_tiles}, {"checked", l.checked}});
  nlohmann::json j = {{"accepted", r.accepted},
                      {"source", r.source},
                      {"source_matches_published", r.source_matches_reference},
                      {"links", links}};
  if (r.accepted)
    j["result_tiles"] = r.result_tiles, j["result_colors"] = r.result_colours;
  else
    j["error"] = r.error;
  return j;
}

void print_report(const certificate::Report& r) {
  for (std::size_t i = 0; i < r.links.size(); ++i)
    fmt::print("link {} {} ({} -> {} tiles): {}\n", i + 1, r.links[i].op, r.links[i].from_tiles, r.links[i].to_tiles,
               r.links[i].checked);
  if (r.accepted)
    fmt::print(
        "accepted: the {} corner tiles ({} colours) are aperiodic if {} is (source tiles match the published set)\n",
        r.result_tiles, r.result_colours, r.source);
  else
    fmt::print("rejected: {}\n", r.error);
}

struct CertifyArgs {
  std::string set = "smallest", out;
};

void run_certify(const CertifyArgs& a, const Context& ctx) {
  if (a.out.empty()) throw InputError("certify needs --out FILE");
  const RecordedChain record = a.set == "smallest"
                                   ? embedded_smallest_record()
                                   : parse_smallest_record(read_input_file(a.set, "chain record", 1 << 20), a.set);
  const nlohmann::json cert = certify_chain(record);
  const certificate::Report r = certificate::check(cert, reference_tiles(record.source));
  if (!r.accepted) throw std::logic_error("certify: the independent checker rejects the certificate: " + r.error);
  write_file_atomic(a.out, cert.dump() + "\n");
  nlohmann::json j = report_json(r);
  j["out"] = a.out;
  j["steps"] = record.steps;
  emit(ctx, j, [&] {
    print_report(r);
    fmt::print("written to {}\n", a.out);
  });
}

void run_check(const std::string& path, const Context& ctx) {
  const nlohmann::json cert = parse_json_input(read_input_file(path, "certificate", kMaxCertificateBytes), path);
  const certificate::Report r = certificate::check(cert, reference_for(cert, path));
  nlohmann::json j = report_json(r);
  j["file"] = path;
  emit(ctx, j, [&] { print_report(r); });
  if (!r.accepted) throw Exit{1};
}

}  // namespace

void add_aperiodic_certificate_commands(CLI::App* ap, Context& ctx) {
  auto* cert = ap->add_subcommand(
      "certify", "Write the certificate of a recorded chain: every link's map and inverse as explicit tables");
  auto a = std::make_shared<CertifyArgs>();
  cert->add_option("SET", a->set,
                   "smallest (the chain of aperiodic/data/smallest-chain.json, the default) or a chain record "
                   "that `aperiodic enumerate --record` wrote");
  cert->add_option("--out", a->out, "The certificate file (JSON, written atomically)")->required();
  add_json_flag(cert, ctx);
  cert->callback([a, &ctx] { run_certify(*a, ctx); });

  auto* check = ap->add_subcommand(
      "check-certificate",
      "Check a certificate with code that shares nothing with the search (certificate/): exit 0 accepted, 1 rejected");
  auto path = std::make_shared<std::string>();
  check->add_option("FILE", *path, "The certificate (what `aperiodic certify` wrote)")->required();
  add_json_flag(check, ctx);
  check->callback([path, &ctx] { run_check(*path, ctx); });
}

}  // namespace tilekit::cli
