// tilekit check FILE [--set SET] [--pegs-out F]: the independent validator on a tiling/packing
// file (cells, or the compact peg form of a corner torus), optionally rewriting it as pegs.
#include <fmt/format.h>

#include <optional>

#include "base/atomic_file.hpp"
#include "cli/command.hpp"
#include "tilesets/tile_set_io.hpp"
#include "tilesets/validator.hpp"

namespace tilekit::cli {

void add_check_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand("check", "Validate a tiling or packing file (JSON) with the independent validator");
  static std::string file, set_name, pegs_out;
  cmd->add_option("FILE", file, "Tiling/packing JSON file")->required();
  cmd->add_option("--set", set_name, "Check that every tile belongs to this tile set (and packs it)");
  cmd->add_option("--pegs-out", pegs_out,
                  "Also write a valid corner torus in the compact peg form (one digit per lattice point)");
  add_json_flag(cmd, ctx);
  cmd->callback([&ctx] {
    Tiling t = read_tiling_file(file);
    std::optional<TileSet> set;
    if (!set_name.empty()) set = resolve_tile_set(set_name);
    ValidationReport rep = validate(t, set ? &*set : nullptr);
    nlohmann::json j = {{"valid", rep.valid},     {"kind", std::string(kind_name(t.kind))},
                        {"colors", t.colours},    {"rows", t.rows},
                        {"cols", t.cols},         {"torus", t.torus},
                        {"packing", rep.packing}, {"errors", rep.errors}};
    if (!pegs_out.empty() && rep.valid) {
      write_file_atomic(pegs_out, tiling_to_peg_json(t).dump(1) + "\n");
      j["pegs_out"] = pegs_out;
    }
    emit(ctx, j, [&] {
      fmt::print("{}: {} {}x{} {} {} tiling: {}{}\n", file, kind_name(t.kind), t.rows, t.cols,
                 t.torus ? "torus" : "bounded", t.colours, rep.valid ? "valid" : "INVALID",
                 rep.packing ? " (a packing: every tile exactly once)" : "");
      for (auto& e : rep.errors) fmt::print("  {}\n", e);
    });
    if (!rep.valid) throw Exit{1};  // well-formed file, but not a valid tiling
  });
}

}  // namespace tilekit::cli
