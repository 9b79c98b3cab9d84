#include "aperiodic/table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <regex>

#include "base/error.hpp"
#include "tilesets/tile_set_io.hpp"

namespace tilekit {

namespace {

// The thesis' printed values (thesis ch. 8, Tables 8.1-8.7), column order 13/5, 14/6,
// 16/6, 24/24, 32/16. These are the reference the recomputation is compared against.
const std::array<std::array<const char*, 5>, 5> kTable81 = {{
    {"125/13", "failed", "failed", "60(13+47)/9", "52/19"},
    {"214/14", "failed", "86/6", "94(14+80)/9", "56/21"},
    {"87/16", "44/6", "44/6", "49(16+33)/12", "64/23"},
    {"203/24", "62/12", "72/12", "67(24+43)/24", "96/49"},
    {"114/32", "failed", "failed", "90(32+58)/28", "128/49"},
}};
const std::array<std::array<const char*, 5>, 5> kTable82 = {{
    {"125/50", "failed", "failed", "60/21", "52/36"},
    {"214/86", "failed", "86/36", "94/23", "56/40"},
    {"87/44", "44/24", "44/24", "49/32", "64/44"},
    {"203/72", "62/42", "72/38", "67/38", "96/72"},
    {"114/84", "failed", "failed", "90/52", "128/96"},
}};
// Iteration tables: [row][column], rows Wang 0, corner 1, Wang 1, ..., corner 4.
using IterTable = std::array<std::array<const char*, 5>, 8>;
const IterTable kTable83 = {{{"13/5", "14/6", "16/6", "24/24", "32/16"},
                             {"125/13", "214/14", "87/16", "203/24", "114/32"},
                             {"125/50", "214/86", "87/44", "203/72", "114/84"},
                             {"1240/125", "3052/214", "286/87", "540/203", "280/114"},
                             {"1240/418", "3052/1208", "286/160", "540/326", "280/204"},
                             {"14810/1240", "58910/3052", "777/286", "2068/540", "662/280"},
                             {"14810/4523", "58910/19274", "777/464", "2068/990", "662/512"},
                             {"160168/14810", "1213029/58910", "1642/777", "7092/2068", "1124/662"}}};
const IterTable kTable84 = {{{"13/5", "14/6", "16/6", "24/24", "32/16"},
                             {"failed", "failed", "44/6", "62/12", "failed"},
                             {"", "", "44/24", "62/42", ""},
                             {"", "", "138/24", "156/42", ""},
                             {"", "", "138/82", "156/104", ""},
                             {"", "", "438/82", "436/104", ""},
                             {"", "", "438/271", "436/272", ""},
                             {"", "", "1406/271", "1154/272", ""}}};
const IterTable kTable85 = {{{"13/5", "14/6", "16/6", "24/24", "32/16"},
                             {"60/9", "94/9", "49/12", "67/24", "90/28"},
                             {"60/21", "94/23", "49/32", "67/38", "90/52"},
                             {"126/42", "210/46", "113/52", "171/76", "212/104"},
                             {"126/84", "210/136", "113/80", "171/118", "212/164"},
                             {"336/149", "596/204", "257/160", "367/224", "464/308"},
                             {"336/228", "596/372", "257/226", "367/292", "464/386"},
                             {"702/456", "1306/744", "545/416", "801/584", "972/772"}}};
const IterTable kTable86 = {{{"13/5", "14/6", "16/6", "24/24", "32/16"},
                             {"52/19", "56/21", "64/23", "96/49", "128/49"},
                             {"52/36", "56/40", "64/44", "96/72", "128/96"},
                             {"208/89", "224/97", "256/109", "384/169", "512/225"},
                             {"208/176", "224/192", "256/216", "384/336", "512/448"},
                             {"832/385", "896/417", "1024/473", "1536/721", "2048/961"},
                             {"832/768", "896/832", "1024/944", "1536/1440", "2048/1920"},
                             {"3328/1601", "3584/1729", "4096/1969", "6144/2977", "8192/3969"}}};
const IterTable kTable87 = {{{"13/5", "14/6", "16/6", "24/24", "32/16"},
                             {"failed", "86/6", "44/6", "72/12", "failed"},
                             {"", "86/36", "44/24", "72/38", ""},
                             {"", "504/36", "138/24", "192/38", ""},
                             {"", "504/216", "138/82", "192/122", ""},
                             {"", "2968/216", "438/82", "564/122", ""},
                             {"", "2968/1272", "438/271", "564/378", ""},
                             {"", "17464/1272", "1406/271", "1584/378", ""}}};

const std::array<ConversionMethod, 5> kMethods = {ConversionMethod::Diagonal, ConversionMethod::Horizontal,
                                                  ConversionMethod::Vertical, ConversionMethod::Rotation,
                                                  ConversionMethod::Subdivision};

Soundness weaker(Soundness a, Soundness b) { return std::max(a, b); }

SetSize corner_size(const Conversion& c, Soundness chain) {
  SetSize s;
  s.tiles = c.size();
  s.colours = c.colours;
  s.rotation = c.method == ConversionMethod::Rotation;
  s.white = c.white;
  s.black = c.black;
  s.soundness = weaker(chain, c.soundness);
  return s;
}

// Parses "125/13", "60(13+47)/9"; nullopt for "failed" or blank.
std::optional<SetSize> parse_thesis(const std::string& t) {
  static const std::regex re(R"((\d+)(?:\((\d+)\+(\d+)\))?/(\d+))");
  std::smatch m;
  if (!std::regex_match(t, m, re)) return std::nullopt;
  SetSize s;
  s.tiles = std::stoul(m[1]);
  s.colours = std::uint32_t(std::stoul(m[4]));
  if (m[2].matched) s.rotation = true, s.white = std::stoul(m[2]), s.black = std::stoul(m[3]);
  return s;
}

TableEntry entry(std::optional<SetSize> ours, const std::string& thesis, const std::string& missing_note = {}) {
  TableEntry e;
  e.ours = ours;
  e.thesis = thesis;
  if (!ours) {
    e.note = missing_note;
    return e;
  }
  auto t = parse_thesis(thesis);
  if (thesis == "failed") {
    e.differs = true;
    e.note = fmt::format("thesis: failed; recomputed set is {}", soundness_name(ours->soundness));
  } else if (t) {
    bool same = t->tiles == ours->tiles && t->colours == ours->colours &&
                (!t->rotation || (t->white == ours->white && t->black == ours->black));
    if (!same) {
      e.differs = true;
      std::vector<std::string> why;
      if (t->tiles != ours->tiles) why.push_back(fmt::format("tiles {} vs {}", ours->tiles, t->tiles));
      if (t->colours != ours->colours) why.push_back(fmt::format("colours {} vs {}", ours->colours, t->colours));
      if (t->rotation && (t->white != ours->white || t->black != ours->black))
        why.push_back(fmt::format("white+black {}+{} vs {}+{}", ours->white, ours->black, t->white, t->black));
      e.note = fmt::format("differs: {}", fmt::join(why, ", "));
    }
  } else if (!thesis.empty()) {
    e.differs = true;
  }
  return e;
}

Conversion run(ConversionMethod m, const std::vector<WangTile>& w, int level) {
  // The translation soundness check is exact at level 1; deeper levels get a smaller budget.
  if (m == ConversionMethod::Horizontal) return horizontal_translation(w, level == 1 ? 200000 : 5000);
  if (m == ConversionMethod::Vertical) return vertical_translation(w, level == 1 ? 200000 : 5000);
  if (m == ConversionMethod::Diagonal) return diagonal_translation(w);
  if (m == ConversionMethod::Rotation) return rotation(w);
  return subdivision(w);
}

}  // namespace

std::string format_size(const SetSize& s) {
  if (s.rotation) return fmt::format("{}({}+{})/{}", s.tiles, s.white, s.black, s.colours);
  return fmt::format("{}/{}", s.tiles, s.colours);
}

const std::vector<TableSource>& table_sources() {
  static const std::vector<TableSource> s = {{"culik-13", "13/5"},   {"kari-14", "14/6"}, {"ammann-gs-16", "16/6"},
                                             {"", "24/24"},          {"", "32/16"},       {"jeandel-rao-11", ""},
                                             {"labbe-19", ""}};
  return s;
}

TablesReport compute_tables(const TableOptions& opts) {
  if (opts.levels < 1) throw InputError(fmt::format("levels must be at least 1, got {}", opts.levels));
  TablesReport rep;
  const auto& sources = table_sources();
  const std::string kMissing = "missing data: the thesis' set is not available";
  std::vector<std::optional<std::vector<WangTile>>> wang;
  for (auto& s : sources) {
    if (s.name.empty()) wang.emplace_back(std::nullopt);
    else wang.emplace_back(relabel_wang(resolve_tile_set(s.name).wang_tiles()));
  }
  auto label = [&](std::size_t i) {
    if (!wang[i]) return sources[i].thesis;
    const auto& w = *wang[i];
    return fmt::format("{} ({}/{})", sources[i].name, w.size(),
                       std::max(wang_horizontal_colours(w), wang_vertical_colours(w)));
  };

  // Tables 8.3-8.7 first: their first two rows are Tables 8.1 and 8.2.
  const std::array<std::pair<const char*, const IterTable*>, 5> iter = {{{"8.3", &kTable83},
                                                                        {"8.4", &kTable84},
                                                                        {"8.7", &kTable87},
                                                                        {"8.5", &kTable85},
                                                                        {"8.6", &kTable86}}};
  std::vector<Table> iter_tables;
  for (std::size_t mi = 0; mi < kMethods.size(); ++mi) {
    Table t;
    t.id = iter[mi].first;
    t.title = fmt::format("Repeated {} (corner) and pairs (Wang, 8.4): tiles/colours", method_name(kMethods[mi]));
    t.corner_label = "set";
    t.rows.push_back("Wang 0");
    for (int l = 1; l <= opts.levels; ++l) t.rows.push_back(fmt::format("corner {}", l)), t.rows.push_back(fmt::format("Wang {}", l));
    if (opts.levels > 1) t.rows.pop_back();  // end with a corner row, as the thesis (keep Wang 1 for 8.2)
    t.cells.assign(t.rows.size(), std::vector<TableEntry>(sources.size()));
    for (std::size_t si = 0; si < sources.size(); ++si) {
      t.columns.push_back(label(si));
      auto thesis = [&](std::size_t row) -> std::string {
        return si < 5 && row < 8 ? (*iter[mi].second)[row][si] : "";
      };
      if (!wang[si]) {
        for (std::size_t r = 0; r < t.rows.size(); ++r) t.cells[r][si] = entry(std::nullopt, thesis(r), kMissing);
        continue;
      }
      std::vector<WangTile> w = *wang[si];
      Soundness chain = Soundness::Conjugate;
      SetSize w0{w.size(), std::max(wang_horizontal_colours(w), wang_vertical_colours(w))};
      t.cells[0][si] = entry(w0, thesis(0));
      std::size_t row = 1;
      for (int l = 1; l <= opts.levels; ++l, row += 2) {
        if (w.size() > opts.max_tiles) {
          for (std::size_t r = row; r < t.rows.size(); ++r)
            t.cells[r][si] = entry(std::nullopt, thesis(r), fmt::format("not computed: beyond {} tiles", opts.max_tiles));
          break;
        }
        Conversion c = run(kMethods[mi], w, l);
        SetSize cs = corner_size(c, chain);
        chain = cs.soundness;
        TableEntry& e = t.cells[row][si] = entry(cs, thesis(row));
        auto printed = parse_thesis(e.thesis);
        if (e.differs && printed && kMethods[mi] == ConversionMethod::Diagonal && printed->tiles == cs.tiles &&
            printed->colours == w.size()) {
          // Diagonal translation: the thesis gives each Wang tile a colour (8.3.1); tiles that
          // occur in no valid 2x2 block give colours no corner tile uses.
          e.explained = true;
          e.note = fmt::format("explained: the thesis counts one colour per Wang tile ({}); {} of them occur in no "
                               "valid 2x2 block, so the corner tiles use {}",
                               w.size(), w.size() - cs.colours, cs.colours);
        }
        rep.largest = std::max(rep.largest, c.size());
        if (row + 1 >= t.rows.size()) break;
        Conversion back = corner_to_wang_pairs(c.corner);
        t.cells[row + 1][si] = entry(SetSize{back.size(), back.colours, 0, 0, false, chain}, thesis(row + 1));
        w = std::move(back.wang);
      }
    }
    iter_tables.push_back(std::move(t));
  }

  // Tables 8.1 and 8.2: rows are the sets, columns the methods (from rows 1 and 2 above).
  for (int which = 0; which < 2; ++which) {
    Table t;
    t.id = which == 0 ? "8.1" : "8.2";
    t.title = which == 0 ? "Aperiodic corner sets from Wang sets: tiles/colours (rotation: tiles(white+black)/colours)"
                         : "Wang sets (8.4) from the corner sets of Table 8.1: tiles/colours";
    t.corner_label = "Wang set";
    const std::array<std::size_t, 5> col_of = {0, 1, 2, 3, 4};  // iter index of each method column
    for (auto m : kMethods) t.columns.push_back(method_name(m) == "horizontal" ? "horizontal translation"
                                                : method_name(m) == "vertical"   ? "vertical translation"
                                                : method_name(m) == "diagonal"   ? "diagonal translation"
                                                                                 : method_name(m));
    for (std::size_t si = 0; si < sources.size(); ++si) {
      t.rows.push_back(label(si));
      std::vector<TableEntry> row;
      for (std::size_t mi : col_of) {
        TableEntry e = iter_tables[mi].cells[std::size_t(which + 1)][si];
        e.thesis = si < 5 ? (which == 0 ? kTable81 : kTable82)[si][mi] : "";
        e = e.ours ? entry(e.ours, e.thesis) : entry(std::nullopt, e.thesis, e.note);
        row.push_back(e);
      }
      t.cells.push_back(row);
    }
    rep.tables.push_back(std::move(t));
  }
  // Thesis order: 8.3 diagonal, 8.4 horizontal, 8.5 rotation, 8.6 subdivision, 8.7 vertical.
  for (const char* id : {"8.3", "8.4", "8.5", "8.6", "8.7"})
    for (auto& t : iter_tables)
      if (t.id == id) rep.tables.push_back(t);
  for (auto& t : rep.tables)
    for (auto& row : t.cells)
      for (auto& e : row) {
        if (e.differs) ++rep.differences;
        if (e.differs && !e.explained) ++rep.unexplained;
        if (!e.ours && !e.note.empty() && e.note.rfind("missing", 0) == 0) ++rep.missing;
      }
  return rep;
}

std::string tables_markdown(const TablesReport& r) {
  std::string out;
  for (const Table& t : r.tables) {
    out += fmt::format("### Table {}: {}\n\nEach cell: recomputed [thesis]; `≠` marks a difference; "
                       "soundness of the chain in italics.\n\n",
                       t.id, t.title);
    out += fmt::format("| {} | {} |\n", t.id == "8.1" || t.id == "8.2" ? "Wang set" : "level", fmt::join(t.columns, " | "));
    out += "|---|";
    for (std::size_t c = 0; c < t.columns.size(); ++c) out += "---|";
    out += "\n";
    std::vector<std::string> notes;
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
      out += "| " + t.rows[r] + " |";
      for (const TableEntry& e : t.cells[r]) {
        std::string cell;
        if (e.ours) cell = format_size(*e.ours) + " _" + soundness_name(e.ours->soundness) + "_";
        else cell = e.note.rfind("missing", 0) == 0 ? "missing" : "—";
        if (!e.thesis.empty()) cell += " [" + e.thesis + "]";
        if (e.differs) cell += e.explained ? " ≠ (explained)" : " ≠";
        out += " " + cell + " |";
        if (e.differs && !e.note.empty()) notes.push_back(fmt::format("{} / {}: {}", t.rows[r], t.columns[&e - t.cells[r].data()], e.note));
      }
      out += "\n";
    }
    if (!notes.empty()) {
      out += "\nDifferences:\n";
      for (auto& n : notes) out += "- " + n + "\n";
    }
    out += "\n";
  }
  return out;
}

}  // namespace tilekit
