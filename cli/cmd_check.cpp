// tilekit check FILE [--set SET] [--pegs-out F]: the independent validator on a tiling/packing
// file (cells, or the compact peg form of a corner torus), optionally rewriting it as pegs.
#include <fmt/format.h>

#include <optional>

#include "base/atomic_file.hpp"
#include "cli/command.hpp"
#include "tilesets/tile_set_io.hpp"
#include "tilesets/validator.hpp"

namespace tilekit::cli {

namespace {

struct CheckArgs {
  std::string file, set_name, pegs_out;
};

void run_check(const CheckArgs& a, const Context& ctx) {
  Tiling t = read_tiling_file(a.file);
  std::optional<TileSet> set;
  if (!a.set_name.empty()) set = resolve_tile_set(a.set_name);
  ValidationReport rep = validate(t, set ? &*set : nullptr);
  nlohmann::json j = {{"valid", rep.valid},     {"kind", std::string(kind_name(t.kind))},
                      {"colors", t.colours},    {"rows", t.rows},
                      {"cols", t.cols},         {"torus", t.torus},
                      {"packing", rep.packing}, {"errors", rep.errors}};
  if (!a.pegs_out.empty() && rep.valid) {
    write_file_atomic(a.pegs_out, tiling_to_peg_json(t).dump(1) + "\n");
    j["pegs_out"] = a.pegs_out;
  }
  emit(ctx, j, [&] {
    fmt::print("{}: {} {}x{} {} {} tiling: {}{}\n", a.file, kind_name(t.kind), t.rows, t.cols,
               t.torus ? "torus" : "bounded", t.colours, rep.valid ? "valid" : "INVALID",
               rep.packing ? " (a packing: every tile exactly once)" : "");
    for (auto& e : rep.errors) fmt::print("  {}\n", e);
  });
  if (!rep.valid) throw Exit{1};  // well-formed file, but not a valid tiling
}

}  // namespace

void add_check_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand("check", "Validate a tiling or packing file (JSON) with the independent validator");
  auto a = std::make_shared<CheckArgs>();
  cmd->add_option("FILE", a->file, "Tiling/packing JSON file")->required();
  cmd->add_option("--set", a->set_name, "Check that every tile belongs to this tile set (and packs it)");
  cmd->add_option("--pegs-out", a->pegs_out,
                  "Also write a valid corner torus in the compact peg form (one digit per lattice point)");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_check(*a, ctx); });
}

}  // namespace tilekit::cli
