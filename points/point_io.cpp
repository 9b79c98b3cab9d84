#include "points/point_io.hpp"

#include <fmt/format.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "base/input.hpp"

namespace tilekit::points {

namespace {

bool ends_with(const std::string& s, const char* suffix) {
  return s.ends_with(suffix);
}
bool is_raw32(const std::string& p) {
  return ends_with(p, ".f32") || ends_with(p, ".bin");
}
bool is_raw64(const std::string& p) { return ends_with(p, ".f64"); }

static_assert(std::endian::native == std::endian::little, "raw point files are little-endian");

}  // namespace

bool is_point_file_path(const std::string& p) {
  return is_raw32(p) || is_raw64(p) || ends_with(p, ".csv");
}

void write_points(const std::string& path, const std::vector<double>& xy) {
  if (is_raw32(path)) {
    const std::vector<float> f(xy.begin(), xy.end());
    write_file_atomic(path, std::string_view(reinterpret_cast<const char*>(f.data()), f.size() * sizeof(float)));
  } else if (is_raw64(path)) {
    write_file_atomic(path, std::string_view(reinterpret_cast<const char*>(xy.data()), xy.size() * sizeof(double)));
  } else if (ends_with(path, ".csv")) {
    std::string out = "x,y\n";
    out.reserve(xy.size() * 12 + 8);
    for (std::size_t i = 0; i + 1 < xy.size(); i += 2) out += fmt::format("{},{}\n", xy[i], xy[i + 1]);
    write_file_atomic(path, out);
  } else {
    throw InputError(fmt::format("{}: unknown point file type (expected .f32, .bin, .f64 or .csv)", path));
  }
}

std::vector<double> read_points(const std::string& path) {
  if (!is_point_file_path(path))
    throw InputError(fmt::format("{}: unknown point file type (expected .f32, .bin, .f64 or .csv)", path));
  const std::string data = read_input_file(path, "point file");
  std::vector<double> xy;
  if (is_raw32(path) || is_raw64(path)) {
    const std::size_t size = is_raw32(path) ? sizeof(float) : sizeof(double);
    if (data.size() % (2 * size) != 0)
      throw InputError(fmt::format("{}: {} bytes is not a whole number of {}-byte points", path, data.size(), 2 * size));
    if (size == sizeof(double)) {
      xy.resize(data.size() / size);
      std::memcpy(xy.data(), data.data(), data.size());
    } else {
      std::vector<float> f(data.size() / size);
      std::memcpy(f.data(), data.data(), data.size());
      xy.assign(f.begin(), f.end());
    }
  } else {
    std::size_t pos = 0;
    int line = 0;
    while (pos < data.size()) {
      const std::size_t end = std::min(data.find('\n', pos), data.size());
      std::string_view l = std::string_view(data).substr(pos, end - pos);
      pos = end + 1;
      ++line;
      if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
      if (l.empty() || (line == 1 && l == "x,y")) continue;
      const std::size_t comma = l.find(',');
      double x = 0, y = 0;
      const auto rx = std::from_chars(l.data(), l.data() + (comma == std::string_view::npos ? l.size() : comma), x);
      const auto ry = comma == std::string_view::npos ? std::from_chars_result{l.data(), std::errc::invalid_argument}
                                                      : std::from_chars(l.data() + comma + 1, l.data() + l.size(), y);
      if (rx.ec != std::errc() || ry.ec != std::errc() || ry.ptr != l.data() + l.size())
        throw InputError(fmt::format("{}:{}: expected 'x,y', got '{}'", path, line, l));
      xy.insert(xy.end(), {x, y});
    }
  }
  for (double v : xy)
    if (!std::isfinite(v)) throw InputError(fmt::format("{}: a coordinate is not a finite number", path));
  return xy;
}

}  // namespace tilekit::points
