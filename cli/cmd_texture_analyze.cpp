// tilekit texture analyze: whether a rendered surface shows its tiles (texture/texture_analysis.hpp,
// texture/README.md): grid repetition, seam ratio, cut visibility, histogram distance and the
// radially averaged power spectrum, on any image and any lattice.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "cli/cmd_texture.hpp"
#include "cli/command.hpp"
#include "texture/exemplar.hpp"
#include "texture/texture_analysis.hpp"

namespace tilekit::cli {

namespace {

namespace fs = std::filesystem;

// Numbers separated by commas, each finite: "--lattice 64,0,32,55.4".
std::vector<double> parse_numbers(const std::string& text, std::size_t count, const char* flag) {
  std::vector<double> v;
  std::size_t at = 0;
  while (at <= text.size() && v.size() <= count) {
    const std::size_t end = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, end - at);
    std::size_t used = 0;
    double x = 0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (item.empty() || used != item.size() || !std::isfinite(x) || std::abs(x) > 1e6)
      throw InputError(fmt::format("{} must be {} numbers separated by commas, got '{}'", flag, count, text));
    v.push_back(x);
    at = end + 1;
  }
  if (v.size() != count)
    throw InputError(fmt::format("{} must be {} numbers separated by commas, got '{}'", flag, count, text));
  return v;
}

struct AnalyzeArgs {
  std::string image, exemplar, labels, lattice, offset, plot;
  int tile_px = 0, threads = 0;
};

// The lattice the tiles sit on: --tile-px T (square) or --lattice AX,AY,BX,BY, and --offset.
Lattice analysis_lattice(const AnalyzeArgs& a) {
  if ((a.tile_px > 0) == !a.lattice.empty())
    throw InputError("give the lattice as either --tile-px T or --lattice AX,AY,BX,BY");
  Lattice l;
  if (a.tile_px > 0) {
    if (a.tile_px < 2 || a.tile_px > 4096)
      throw InputError(fmt::format("--tile-px must be 2..4096, got {}", a.tile_px));
    l = Lattice::square(a.tile_px);
  } else {
    const std::vector<double> v = parse_numbers(a.lattice, 4, "--lattice");
    l.a = {v[0], v[1]};
    l.b = {v[2], v[3]};
  }
  if (!a.offset.empty()) {
    const std::vector<double> v = parse_numbers(a.offset, 2, "--offset");
    l.offset = {v[0], v[1]};
  }
  return l;
}

// Refuses a --plot path that cannot be written before the analysis runs.
void check_plot_path(const std::string& plot) {
  if (const fs::path dir = fs::path(plot).parent_path(); !plot.empty() && !dir.empty()) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
      throw InputError(fmt::format("{}: no folder {} to write the plot in", plot, dir.string()));
  }
  if (std::error_code ec; !plot.empty() && fs::is_directory(plot, ec)) {
    throw InputError(fmt::format("{}: is a folder, not a file to write the plot to", plot));
  }
}

template <class T>
nlohmann::json measure_or_null(const std::optional<T>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json();
}

nlohmann::json analysis_json(const AnalyzeArgs& a, const Lattice& l, const TextureAnalysis& r,
                             const std::string& exemplar_name) {
  nlohmann::json lags = nlohmann::json::array();
  for (const LagValue& v : r.lattice_lags) lags.push_back({{"lag", {v.dx, v.dy}}, {"r", v.r}});
  nlohmann::json j = {
      {"image", a.image},
      {"width", r.width},
      {"height", r.height},
      {"lattice", {{"a", l.a}, {"b", l.b}, {"offset", l.offset}}},
      {"grid_repetition", r.grid_repetition},
      {"lattice_correlation", r.lattice_correlation},
      {"reference_correlation", r.reference_correlation},
      {"reference_lags", r.reference_lags},
      {"lattice_lags", lags},
      {"seam_ratio", measure_or_null(r.seam_ratio)},
      {"cut_visibility", measure_or_null(r.cut_visibility)},
      {"line_continuity", measure_or_null(r.line_continuity)},
      {"border_continuity", r.line_continuity ? nlohmann::json(r.border_continuity) : nlohmann::json()},
      {"interior_continuity", r.line_continuity ? nlohmann::json(r.interior_continuity) : nlohmann::json()},
      {"histogram_distance", measure_or_null(r.histogram_distance)},
      {"histogram_emd", measure_or_null(r.histogram_emd)},
      {"lattice_peak_db", r.spectrum.lattice_peak_db},
      {"lattice_frequencies", r.spectrum.lattice_frequencies},
      {"plot", a.plot.empty() ? nlohmann::json() : nlohmann::json(a.plot)}};
  if (!exemplar_name.empty()) j["exemplar"] = exemplar_name;
  return j;
}

void print_analysis(const AnalyzeArgs& a, const Lattice& l, const TextureAnalysis& r,
                    const std::string& exemplar_name) {
  fmt::print("{}: {}x{}, lattice ({:g},{:g}) ({:g},{:g})\n", a.image, r.width, r.height, l.a[0], l.a[1], l.b[0],
             l.b[1]);
  fmt::print("grid repetition  {:.3f}  (R at the lattice lags {:.3f} - mean |R| at {} reference lags {:.3f})\n",
             r.grid_repetition, r.lattice_correlation, r.reference_lags, r.reference_correlation);
  if (r.seam_ratio) fmt::print("seam ratio       {:.3f}\n", *r.seam_ratio);
  if (r.cut_visibility) fmt::print("cut visibility   {:.3f}\n", *r.cut_visibility);
  if (r.line_continuity)
    fmt::print("line continuity  {:.3f}  (lines across tile borders {:.3f} / between them {:.3f})\n",
               *r.line_continuity, r.border_continuity, r.interior_continuity);
  if (r.histogram_emd)
    fmt::print("histogram EMD    {:.2f} grey levels (R {:.2f}, G {:.2f}, B {:.2f}) to {}\n", *r.histogram_distance,
               (*r.histogram_emd)[0], (*r.histogram_emd)[1], (*r.histogram_emd)[2], exemplar_name);
  fmt::print("lattice peak     {:+.1f} dB in the power spectrum{}\n", r.spectrum.lattice_peak_db,
             a.plot.empty() ? "" : "; plot: " + a.plot);
}

void run_analyze(const AnalyzeArgs& a, const Context& ctx) {
  const Lattice l = analysis_lattice(a);
  const int threads = resolve_threads(a.threads);
  const Image img = read_image(a.image);
  std::optional<Image> exemplar, labels;
  std::string exemplar_name;
  if (!a.exemplar.empty()) {
    Exemplar e = load_exemplar(a.exemplar);
    exemplar_name = e.name;
    exemplar = std::move(e.image);
  }
  if (!a.labels.empty()) labels = read_image(a.labels);
  check_plot_path(a.plot);
  const TextureAnalysis r =
      analyze_texture(img, l, exemplar ? &*exemplar : nullptr, labels ? &*labels : nullptr, threads);
  if (!a.plot.empty()) write_png(a.plot, spectrum_plot(r, fs::path(a.image).filename().string()));
  emit(ctx, analysis_json(a, l, r, exemplar_name), [&] { print_analysis(a, l, r, exemplar_name); });
}

}  // namespace

void add_texture_analyze(CLI::App& texture, Context& ctx) {
  auto* cmd = texture.add_subcommand(
      "analyze", "Measure how a rendered texture shows its tiles: grid repetition, seams, cuts, histogram, spectrum");
  auto a = std::make_shared<AnalyzeArgs>();
  cmd->add_option("IMG", a->image, "The rendered surface (PNG or JPEG)")->required();
  cmd->add_option("--tile-px", a->tile_px, "Tile size T in pixels: the square lattice the tiles sit on");
  cmd->add_option(
      "--lattice", a->lattice,
      "Another lattice instead of --tile-px: its basis AX,AY,BX,BY in pixels (hex-tiling: S,0,S/2,S*0.866)");
  cmd->add_option("--offset", a->offset, "A lattice point (tile corner) in image pixels, X,Y (default 0,0)");
  cmd->add_option("--exemplar", a->exemplar,
                  "The exemplar, for the histogram distance (a file, or a fetched real texture by name)");
  cmd->add_option("--labels", a->labels,
                  "Sample labels of the same view (a PNG, one colour per sample), for the cut visibility");
  cmd->add_option("--plot", a->plot, "Write the radially averaged power spectrum with the lattice frequencies (PNG)");
  cmd->add_option("--threads", a->threads, "Threads (default: every core)");
  add_json_flag(cmd, ctx);
  cmd->callback([a, &ctx] { run_analyze(*a, ctx); });
}

}  // namespace tilekit::cli
