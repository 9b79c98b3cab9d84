#pragma once
// Point files: raw little-endian float32 pairs x0 y0 x1 y1 ... (.f32 or .bin, 8 bytes a point),
// float64 pairs (.f64, 16 bytes a point: exact far from the origin, where float32 loses the
// disk radius), or CSV with a header line "x,y" (.csv, every digit of the doubles). Written
// atomically.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "base/atomic_file.hpp"

namespace tilekit::points {

bool is_point_file_path(const std::string& path);  // .f32, .bin, .f64 or .csv
void write_points(const std::string& path, const std::vector<double>& xy);
// The checks PointFileWriter makes, for a caller to make before its work: InputError for an unknown
// extension, or float32 output that would round coordinates as large as `largest` by more than
// 1% of the points' mean `spacing`.
void check_point_file(const std::string& path, double largest, double spacing);

// A point file written a piece at a time (`points generate` streams a window row by row, so its
// size is bounded by the disk, not the memory) and put in place whole by commit(); destroyed
// before, it leaves `path` as it was. float32 output is refused up front (InputError) when it
// would round a coordinate as large as `largest` (in absolute value) by more than 1% of the
// points' mean `spacing`; an unknown extension is refused too.
class PointFileWriter {
 public:
  PointFileWriter(const std::string& path, double largest, double spacing);
  void append(const double* xy, std::size_t points);  // interleaved x, y
  void commit();
  std::uint64_t points() const { return points_; }

 private:
  void flush();
  enum class Format { F32, F64, Csv } format_;
  AtomicFileWriter out_;
  std::string buffer_;
  std::uint64_t points_ = 0;
};
// InputError naming the file for an unknown extension, a size that is not a whole number of
// points, or a malformed CSV line.
std::vector<double> read_points(const std::string& path);

}  // namespace tilekit::points
