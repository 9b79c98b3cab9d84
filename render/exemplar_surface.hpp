#pragma once
// What the two baselines of tile-based texture mapping sample (`texture render --method hex|hpn`):
// the exemplar itself, with no precomputed tiles. Both cover the plane with a triangle grid
// (Heitz & Neyret 2018; Mikkelsen 2022 uses the same grid): every vertex shows a patch
// of the exemplar around a random centre, and a pixel blends the patches of the three vertices of
// its triangle (render/baseline_samplers.hpp).
//  - hex tiling (Mikkelsen 2022, "Practical Real-Time Hex-Tiling", JCGT 11(3)) samples the
//    exemplar's mip chain (`levels`).
//  - histogram-preserving blending (Heitz & Neyret 2018, "High-Performance By-Example Noise using
//    a Histogram-Preserving Blending Operator", HPG) samples the exemplar with its colours
//    decorrelated (PCA) and every channel "Gaussianized" by its histogram (T(x) = G^-1(H(x)),
//    G a Gaussian of mean 1/2 and deviation 1/6), and maps the blend back through the inverse
//    transformation, a look-up table prefiltered per mip level.
//
// One deviation from both papers, for exemplars that do not tile: patch centres are drawn inside
// the exemplar, far enough from its border that no patch reaches across it (the papers assume a
// tileable input and offset patches anywhere, wrapping around, which shows the exemplar's border
// as a cut inside a patch otherwise).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace tilekit {

// RGBA floats, row-major, row 0 at the top.
struct FloatImage {
  int width = 0, height = 0;
  std::vector<float> texels;  // width * height * 4
  float* at(int x, int y) { return &texels[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4]; }
  const float* at(int x, int y) const { return &texels[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4]; }
};

// IEEE 754 binary16 (what RGBA16F textures hold), round to nearest even, and back. Every float
// the GPU reads from a half-float texture passes through these on the CPU side too.
std::uint16_t float_to_half(float f);
float half_to_float(std::uint16_t h);

inline constexpr int kLutWidth = 256;  // entries of the inverse transformation per mip level

struct ExemplarSurface {
  std::string name;
  int width = 0, height = 0;
  float cell_px = 0;                     // triangle side in texels (the radius of a vertex's hexagon)
  float centre_lo[2]{}, centre_hi[2]{};  // patch centres are drawn in [lo, hi] (texels, x and y)
  std::vector<Image> levels;             // the exemplar's mip chain (RGBA8), for hex tiling
  // Histogram-preserving blending:
  std::vector<FloatImage> gaussian;          // the Gaussianized exemplar's mip chain, half-float values
  FloatImage lut;                            // kLutWidth x levels: the inverse transformation per level, / 255
  std::array<float, 9> basis{};              // colour / 255 = mean + basis * value (column-major 3x3: PCA)
  std::array<float, 3> mean{};               // mean colour / 255
  std::size_t memory_bytes(bool hpn) const;  // texture memory a GPU holds for the method
};

// The surface of an exemplar image. cell_px 0 picks the papers' grid scale, a triangle side of
// min(width, height) / (2 sqrt 3) (their uv * 2 sqrt 3, for a texture repeating every unit).
// InputError when the exemplar is too small for the cell (a patch must fit inside it).
ExemplarSurface make_exemplar_surface(const Image& exemplar, std::string name, float cell_px = 0);

}  // namespace tilekit
