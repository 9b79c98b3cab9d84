#include "solver/colour_lift_model.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "base/error.hpp"
#include "tilesets/constructions.hpp"
#include "tilesets/validator.hpp"

namespace tilekit {

std::string LiftSpec::text() const {
  return fmt::format("m={}", base_colours) + (base_file.empty() ? "" : ",base=" + base_file);
}

LiftSpec parse_lift_spec(const std::string& text) {
  auto fail = [&](const std::string& why) { return RequestError("lift", fmt::format("`lift` '{}': {}", text, why)); };
  LiftSpec spec;
  std::size_t at = 0;
  bool have_m = false;
  while (at <= text.size()) {
    const std::size_t end = std::min(text.find(',', at), text.size());
    const std::string field = text.substr(at, end - at);
    const std::size_t eq = field.find('=');
    const std::string key = eq == std::string::npos ? (at == 0 ? "m" : field) : field.substr(0, eq);
    const std::string value = eq == std::string::npos ? field : field.substr(eq + 1);
    if (key == "m") {
      std::size_t used = 0;
      long long m = -1;
      try {
        m = std::stoll(value, &used);
      } catch (const std::exception&) {
      }
      if (used != value.size() || m < 1 || m > 255) throw fail("the base colour count must be an integer in 1..255");
      spec.base_colours = std::uint32_t(m);
      have_m = true;
    } else if (key == "base" && eq != std::string::npos) {
      spec.base_file = text.substr(at + eq + 1);  // the rest of the text, commas included
      if (spec.base_file.empty()) throw fail("base= needs a packing file");
      break;
    } else {
      throw fail(fmt::format("unknown field '{}' (expected M, m=M or base=FILE)", field));
    }
    at = end + 1;
  }
  if (!have_m) throw fail("missing the base colour count (e.g. `lift` 4 or `lift` m=4,base=FILE)");
  return spec;
}

std::string lift_with_absolute_base(const std::string& text) {
  if (text.empty()) return text;
  LiftSpec spec = parse_lift_spec(text);
  if (spec.base_file.empty() || std::filesystem::path(spec.base_file).is_absolute()) return text;
  spec.base_file = std::filesystem::absolute(spec.base_file).lexically_normal().string();
  return spec.text();
}

LiftProblem make_lift_problem(TileKind kind, std::uint32_t colours, const LiftSpec& spec) {
  const std::uint32_t m = spec.base_colours;
  if (m == 0 || colours % m != 0 || colours / m < 2)
    throw RequestError(
        "lift", fmt::format("`lift` {}: {} colours are not a multiple k*{} with k >= 2", spec.text(), colours, m));
  LiftProblem p;
  p.spec = spec;
  p.colours = colours;
  p.quotient_colours = colours / m;
  if (!spec.base_file.empty()) {
    try {
      p.base = read_tiling_file(spec.base_file);
    } catch (const InputError& e) {
      throw RequestError("lift", fmt::format("`lift` {}: {}", spec.text(), e.what()));
    }
    p.base_how = spec.base_file;
  } else {
    auto built = construct_packing(kind, m);
    if (!built)
      throw RequestError("lift",
                         fmt::format("`lift` {}: no {} packing over {} colours is known to lift from (give base=FILE)",
                                     spec.text(), kind_name(kind), m));
    p.base = std::move(built->tiling);
    p.base_how = built->how;
  }
  const int side = int(m * m);
  if (p.base.kind != kind || p.base.ch() != m || p.base.cv() != m || !p.base.torus || p.base.rows != side ||
      p.base.cols != side || !validate(p.base).packing)
    throw RequestError("lift",
                       fmt::format("`lift` {}: the base {} is not a {} packing over {} colours on the {}x{} torus",
                                   spec.text(), p.base_how, kind_name(kind), m, side, side));
  p.period = side;
  const std::uint32_t k = p.quotient_colours;
  p.quotient.set = kind == TileKind::Wang ? complete_wang_set(k, k) : complete_corner_set(k);
  p.quotient.rows = p.quotient.cols = int(k * k) * side;
  p.quotient.torus = true;
  p.quotient.packing = true;  // per residue class mod the period (LatticeModel's class period)
  return p;
}

}  // namespace tilekit
