#pragma once
// Thesis Tables 8.1-8.7 recomputed (`tilekit aperiodic table`): the ch. 8 constructions
// applied to the published aperiodic Wang sets, then iterated (corner -> Wang (8.4) ->
// corner ...), each entry next to the value the thesis prints, differences marked.
// The thesis' 24/24 and 32/16 sets are not available as data and show as missing;
// jeandel-rao-11 and labbe-19 are extra rows (columns in 8.3-8.7) no published table has.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "aperiodic/convert.hpp"

namespace tilekit {

// One tile set in a table: tiles/colours, plus white+black for rotation (Table 8.1).
struct SetSize {
  std::size_t tiles = 0;
  std::uint32_t colours = 0;
  std::size_t white = 0, black = 0;  // rotation only
  bool rotation = false;
  Soundness soundness = Soundness::Conjugate;  // of the whole chain from the published set
};
std::string format_size(const SetSize& s);  // "125/13" or "60(13+47)/9"

struct TableEntry {
  std::optional<SetSize> ours;  // nullopt: missing data, or not computed (see note)
  std::string thesis;           // as printed: "125/13", "failed", "" (blank)
  bool differs = false;         // ours and the thesis disagree (any number, or failed vs a set)
  bool explained = false;       // the difference is accounted for (see note)
  std::string note;             // why it differs or is missing
};

struct Table {
  std::string id, title;
  std::string corner_label;                // header of the first column
  std::vector<std::string> columns, rows;  // cells[row][col]
  std::vector<std::vector<TableEntry>> cells;
};

struct TableOptions {
  int levels = 4;                     // corner sets per iteration column (thesis: 4)
  std::size_t max_tiles = 20'000'000; // stop iterating a column beyond this size
};

struct TablesReport {
  std::vector<Table> tables;  // 8.1, 8.2, 8.3, 8.4, 8.5, 8.6, 8.7
  std::size_t differences = 0, unexplained = 0, missing = 0, largest = 0;
};

// The published Wang sets of the tables, in thesis column order, plus the extra ones.
struct TableSource {
  std::string name;    // built-in set name ("" when the data is missing)
  std::string thesis;  // the thesis' label, e.g. "13/5" ("" for extra rows)
};
const std::vector<TableSource>& table_sources();

TablesReport compute_tables(const TableOptions& opts = {});

std::string tables_markdown(const TablesReport& r);

}  // namespace tilekit
