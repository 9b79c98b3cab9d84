#pragma once
// Point files: raw little-endian float32 pairs x0 y0 x1 y1 ... (.f32 or .bin, 8 bytes a point)
// or CSV with a header line "x,y" (.csv). Written atomically.
#include <string>
#include <vector>

namespace tilekit::points {

bool is_point_file_path(const std::string& path);  // .f32, .bin or .csv
void write_points(const std::string& path, const std::vector<float>& xy);
// InputError naming the file for an unknown extension, a size that is not a whole number of
// points, or a malformed CSV line.
std::vector<float> read_points(const std::string& path);

}  // namespace tilekit::points
