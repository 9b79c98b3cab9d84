#include "texture/exemplar.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>

#include "base/error.hpp"

namespace tilekit {

Exemplar exemplar_from_image(Image image, std::string name) {
  if (image.width < kMinExemplarSide || image.height < kMinExemplarSide)
    throw InputError(fmt::format("{}: the exemplar is {}x{} pixels, too small for texture tiles (at least {}x{})", name,
                                 image.width, image.height, kMinExemplarSide, kMinExemplarSide));
  Exemplar e;
  e.image = std::move(image);
  e.name = std::move(name);
  double sum = 0, steps = 0;
  std::size_t pairs = 0;
  for (int y = 0; y + 1 < e.height(); ++y)
    for (int x = 0; x + 1 < e.width(); ++x) {
      sum += colour_distance(e.at(x, y), e.at(x + 1, y)) + colour_distance(e.at(x, y), e.at(x, y + 1));
      steps += channel_step(e.at(x, y), e.at(x + 1, y)) + channel_step(e.at(x, y), e.at(x, y + 1));
      pairs += 2;
    }
  e.neighbour_difference = std::max(1.0, sum / double(pairs));  // a flat image still gets a unit
  e.mean_step = std::max(0.5, steps / double(pairs));
  return e;
}

Exemplar load_exemplar(const std::string& path_or_name) {
  std::error_code ec;
  std::string path = path_or_name;
  if (!std::filesystem::exists(path, ec)) {
    const std::string cached = real_texture_path(path_or_name);
    if (!cached.empty()) path = cached;
  }
  return exemplar_from_image(read_image(path), path);
}

std::string texture_cache_dir() {
  if (const char* dir = std::getenv("TILEKIT_TEXTURES"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/tilekit/textures";
  const char* home = std::getenv("HOME");
  return std::string(home && *home ? home : ".") + "/.cache/tilekit/textures";
}

const std::vector<std::string>& real_texture_names() {
  static const std::vector<std::string> names = {"brick", "grass", "gravel"};
  return names;
}

std::string real_texture_path(const std::string& name) {
  if (name.empty() || name.find('/') != std::string::npos) return "";
  std::error_code ec;
  const std::string path = texture_cache_dir() + "/" + name + ".png";
  return std::filesystem::is_regular_file(path, ec) ? path : "";
}

}  // namespace tilekit
