// OpenEXR through the OpenEXR library (Debian libopenexr-dev; its C++ API, single-threaded): files
// read from and written to memory (read_image reads the file whole through read_input_file; write_exr
// (image.cpp) renames a complete file into place). Every exception of the library becomes one InputError.
#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.hpp"
#include "image/codecs.hpp"
#include "image/image.hpp"

namespace tilekit {

namespace {

class MemoryIStream : public Imf::IStream {
 public:
  MemoryIStream(std::string_view bytes, const std::string& name) : Imf::IStream(name.c_str()), bytes_(bytes) {}
  bool read(char c[], int n) override {
    if (n < 0 || at_ > bytes_.size() || std::uint64_t(n) > bytes_.size() - at_)
      throw std::runtime_error("the file ends early");
    std::memcpy(c, bytes_.data() + at_, std::size_t(n));
    at_ += std::uint64_t(n);
    return at_ < bytes_.size();
  }
  std::uint64_t tellg() override { return at_; }
  void seekg(std::uint64_t pos) override { at_ = pos; }

 private:
  std::string_view bytes_;
  std::uint64_t at_ = 0;
};

class StringOStream : public Imf::OStream {
 public:
  StringOStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    if (n <= 0) return;
    if (bytes.size() < at_ + std::size_t(n)) bytes.resize(at_ + std::size_t(n));
    std::memcpy(bytes.data() + at_, c, std::size_t(n));
    at_ += std::size_t(n);
  }
  std::uint64_t tellp() override { return at_; }
  void seekp(std::uint64_t pos) override { at_ = std::size_t(pos); }
  std::string bytes;

 private:
  std::size_t at_ = 0;
};

}  // namespace

namespace image_codecs {

bool is_exr(std::string_view file) {
  return file.starts_with(std::string_view("\x76\x2f\x31\x01", 4));
}

Image decode_exr(const std::string& path, std::string_view file, int channels, bool keep_depth) {
  try {
    MemoryIStream stream(file, path);
    Imf::InputFile in(stream, 0);
    const Imath::Box2i dw = in.header().dataWindow();
    const std::int64_t w = std::int64_t(dw.max.x) - dw.min.x + 1, h = std::int64_t(dw.max.y) - dw.min.y + 1;
    if (w < 1 || h < 1) throw InputError(fmt::format("{}: an OpenEXR image of {}x{} texels", path, w, h));
    check_decoded_size(path, file.size(), w, h);
    // R, G, B (+ A), or Y (+ A), or one channel of any name (a height or depth map).
    const Imf::ChannelList& list = in.header().channels();
    std::vector<std::string> names;
    const auto has = [&](const char* n) { return list.findChannel(n) != nullptr; };
    if (has("R") && has("G") && has("B"))
      names = {"R", "G", "B"};
    else if (has("Y"))
      names = {"Y"};
    else if (list.begin() != list.end() && ++list.begin() == list.end())
      names = {list.begin().name()};
    if (names.empty())
      throw InputError(fmt::format("{}: an OpenEXR image without R, G, B or Y channels or a single channel", path));
    if (names.size() != 1 || names[0] == "Y")
      if (has("A")) names.push_back("A");
    for (const std::string& n : names)
      if (const Imf::Channel* c = list.findChannel(n); c->xSampling != 1 || c->ySampling != 1)
        throw InputError(fmt::format("{}: OpenEXR channel {} is subsampled", path, n));
    const std::size_t n = names.size();
    std::vector<std::uint8_t> bytes(std::size_t(w) * std::size_t(h) * n * sizeof(float));
    Imf::FrameBuffer fb;
    for (std::size_t k = 0; k < n; ++k)
      fb.insert(names[k], Imf::Slice::Make(Imf::FLOAT, bytes.data() + k * sizeof(float), dw, n * sizeof(float),
                                           n * sizeof(float) * std::size_t(w)));
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    Image img = from_channels(int(w), int(h), 32, int(n), std::move(bytes), channels);
    return keep_depth ? img : img.to_depth(8);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(fmt::format("{}: cannot read the OpenEXR image ({})", path, e.what()));
  }
}

}  // namespace image_codecs

std::string encode_exr(const Image& img) {
  if (img.depth != 32 || (img.channels != 1 && img.channels != 4))
    throw InputError(fmt::format("an OpenEXR image is written from 32-bit float grey or RGBA, not {}-bit {}-channel",
                                 img.depth, img.channels));
  try {
    StringOStream out;
    {
      Imf::Header header(img.width, img.height);
      header.compression() = Imf::ZIP_COMPRESSION;  // lossless
      const std::vector<const char*> names =
          img.channels == 1 ? std::vector<const char*>{"Y"} : std::vector<const char*>{"R", "G", "B", "A"};
      for (const char* n : names) header.channels().insert(n, Imf::Channel(Imf::FLOAT));
      Imf::OutputFile file(out, header, 0);
      Imf::FrameBuffer fb;
      const std::size_t texel = std::size_t(img.texel_bytes());
      auto* base = const_cast<char*>(reinterpret_cast<const char*>(img.pixels.data()));
      for (std::size_t k = 0; k < names.size(); ++k)
        fb.insert(names[k], Imf::Slice(Imf::FLOAT, base + k * sizeof(float), texel, texel * std::size_t(img.width)));
      file.setFrameBuffer(fb);
      file.writePixels(img.height);
    }  // the file's destructor writes its line offsets
    return std::move(out.bytes);
  } catch (const std::exception& e) {
    throw InputError(fmt::format("cannot encode a {}x{} OpenEXR image ({})", img.width, img.height, e.what()));
  }
}

}  // namespace tilekit
