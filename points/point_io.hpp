#pragma once
// Point files: raw little-endian float32 pairs x0 y0 x1 y1 ... (.f32 or .bin, 8 bytes a point),
// float64 pairs (.f64, 16 bytes a point: exact far from the origin, where float32 loses the
// disk radius), or CSV with a header line "x,y" (.csv, every digit of the doubles). Written
// atomically.
#include <string>
#include <vector>

namespace tilekit::points {

bool is_point_file_path(const std::string& path);  // .f32, .bin, .f64 or .csv
void write_points(const std::string& path, const std::vector<double>& xy);
// InputError naming the file for an unknown extension, a size that is not a whole number of
// points, or a malformed CSV line.
std::vector<double> read_points(const std::string& path);

}  // namespace tilekit::points
