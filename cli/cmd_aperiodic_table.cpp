// tilekit aperiodic table: thesis Tables 8.1-8.7 recomputed, next to the printed values.
#include <fmt/format.h>

#include <chrono>

#include "cli/cmd_aperiodic.hpp"
#include "tilesets/aperiodic_table.hpp"

namespace tilekit::cli {

namespace {

nlohmann::json size_json(const SetSize& s) {
  nlohmann::json j = {{"tiles", s.tiles}, {"colors", s.colours}, {"soundness", soundness_name(s.soundness)}};
  if (s.rotation) j["white"] = s.white, j["black"] = s.black;
  return j;
}

nlohmann::json tables_json(const TablesReport& r) {
  nlohmann::json tables = nlohmann::json::array();
  for (const Table& t : r.tables) {
    nlohmann::json cells = nlohmann::json::array();
    for (auto& row : t.cells) {
      nlohmann::json jr = nlohmann::json::array();
      for (auto& e : row)
        jr.push_back({{"ours", e.ours ? size_json(*e.ours) : nlohmann::json()},
                      {"text", e.ours ? format_size(*e.ours) : "missing"},
                      {"thesis", e.thesis},
                      {"differs", e.differs},
                      {"explained", e.explained},
                      {"note", e.note}});
      cells.push_back(jr);
    }
    tables.push_back({{"id", t.id}, {"title", t.title}, {"columns", t.columns}, {"rows", t.rows}, {"cells", cells}});
  }
  return {{"tables", tables}, {"differences", r.differences}, {"unexplained", r.unexplained}, {"missing", r.missing}, {"largest_set", r.largest}};
}

}  // namespace

void add_aperiodic_table_command(CLI::App* ap, Context& ctx) {
  auto* cmd = ap->add_subcommand("table", "Recompute thesis Tables 8.1-8.7 and compare with the printed values");
  static TableOptions opts;
  cmd->add_option("--levels", opts.levels, "Corner sets per iteration column (thesis: 4)")->check(CLI::Range(1, 6));
  add_json_flag(cmd, ctx);
  cmd->callback([&ctx] {
    auto t0 = std::chrono::steady_clock::now();
    TablesReport r = compute_tables(opts);
    double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    nlohmann::json j = tables_json(r);
    j["seconds"] = secs;
    emit(ctx, j, [&] {
      fmt::print("{}", tables_markdown(r));
      fmt::print("{} entries differ from the thesis ({} not explained), {} are missing data; largest set {} tiles; {:.2f} s\n",
                 r.differences, r.unexplained, r.missing, r.largest, secs);
    });
  });
}

}  // namespace tilekit::cli
