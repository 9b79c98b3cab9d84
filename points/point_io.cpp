#include "points/point_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <iterator>

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

namespace {

// float32 keeps 24 bits: far from the origin its rounding reaches the spacing of the points
// (at 1e6 it is 0.06, near the spacing at density 100) and points collapse onto each other.
// Refused when the rounding exceeds 1% of the mean spacing.
void check_float32_fits(const std::string& path, double largest, double spacing) {
  const double rounding = largest * 0x1p-24;
  if (rounding > 0.01 * spacing)
    throw InputError(fmt::format("{}: float32 rounds coordinates as large as {:.6g} by up to {:.3g}, more than 1% of "
                                 "the points' spacing ({:.3g}); write .f64 or .csv instead",
                                 path, largest, rounding, spacing));
}

void check_extension(const std::string& path) {
  if (!is_point_file_path(path))
    throw InputError(fmt::format("{}: unknown point file type (expected .f32, .bin, .f64 or .csv)", path));
}

constexpr std::size_t kFlushBytes = std::size_t(1) << 20;

}  // namespace

void check_point_file(const std::string& path, double largest, double spacing) {
  check_extension(path);
  if (is_raw32(path)) check_float32_fits(path, largest, spacing);
}

PointFileWriter::PointFileWriter(const std::string& path, double largest, double spacing)
    : format_(is_raw32(path) ? Format::F32 : is_raw64(path) ? Format::F64 : Format::Csv),
      out_((check_extension(path), path)) {
  if (format_ == Format::F32) check_float32_fits(path, largest, spacing);
  if (format_ == Format::Csv) buffer_ = "x,y\n";
}

void PointFileWriter::append(const double* xy, std::size_t points) {
  for (std::size_t i = 0; i < 2 * points; i += 2) {
    switch (format_) {
      case Format::F32: {
        const float f[2] = {float(xy[i]), float(xy[i + 1])};
        buffer_.append(reinterpret_cast<const char*>(f), sizeof f);
        break;
      }
      case Format::F64:
        buffer_.append(reinterpret_cast<const char*>(xy + i), 2 * sizeof(double));
        break;
      case Format::Csv:
        fmt::format_to(std::back_inserter(buffer_), "{},{}\n", xy[i], xy[i + 1]);
        break;
    }
    if (buffer_.size() >= kFlushBytes) flush();
  }
  points_ += points;
}

void PointFileWriter::flush() {
  out_.write(buffer_);
  buffer_.clear();
}

void PointFileWriter::commit() {
  flush();
  out_.commit();
}

void write_points(const std::string& path, const std::vector<double>& xy) {
  check_extension(path);
  const std::size_t n = xy.size() / 2;
  double largest = 0, spacing = 1e300;
  if (n >= 2) {  // the extent and mean spacing of the points themselves
    double x0 = xy[0], x1 = xy[0], y0 = xy[1], y1 = xy[1];
    for (std::size_t i = 0; i < xy.size(); i += 2) {
      x0 = std::min(x0, xy[i]), x1 = std::max(x1, xy[i]), y0 = std::min(y0, xy[i + 1]), y1 = std::max(y1, xy[i + 1]);
      largest = std::max({largest, std::abs(xy[i]), std::abs(xy[i + 1])});
    }
    spacing = std::sqrt(std::max(x1 - x0, 1e-300) * std::max(y1 - y0, 1e-300) / double(n));
  }
  PointFileWriter out(path, largest, spacing);
  out.append(xy.data(), n);
  out.commit();
}

std::vector<double> read_points(const std::string& path) {
  check_extension(path);
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
