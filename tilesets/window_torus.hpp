#pragma once
// Window tori: colourings P of the R x S torus over C symbols, read through K x L windows. A
// de Bruijn torus (perfect map) (R,S;K,L)_C holds every one of the C^(KL) windows exactly once,
// so RS = C^(KL). Binary ones exist exactly when RS = 2^(KL), R > K (or R = K = 1) and S > L
// (or S = L = 1) (Paterson 1994, "Perfect maps", IEEE Trans. IT 40); a corner packing over C
// colours is the (C^2,C^2;2,2)_C case (tile_grid.hpp).
//
// A window torus is a Tiling of kind Window: cell (r,c) holds the index of the window whose
// top-left symbol is P(r,c), its K*L symbols read row by row, the first one most significant:
//   index = sum over a < K, b < L of P(r+a, c+b) * C^(KL-1 - (aL+b))   (indices mod R and S).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tilesets/tile_grid.hpp"

namespace tilekit {

// The number of K x L windows over C symbols, C^(KL); 0 when it exceeds `limit`.
std::uint64_t window_count(std::uint32_t colours, int rows, int cols, std::uint64_t limit);

// Checks that an R x S torus can hold every K x L window over C symbols once, and throws
// InputError naming the reason otherwise: a side of 0, a window larger than the torus, more
// windows than kMaxTiles, or RS != C^(KL).
void check_window_torus_shape(std::uint32_t colours, int window_rows, int window_cols, int rows, int cols);

// The window torus of the pegs P (R x S, row-major, symbols below C).
Tiling window_torus_from_pegs(const std::vector<Colour>& pegs, int rows, int cols, std::uint32_t colours,
                              int window_rows, int window_cols);
// The pegs of a window torus: the top-left symbol of every cell's window.
std::vector<Colour> pegs_of_window_torus(const Tiling& t);

// A corner torus as the window torus of its pegs with 2 x 2 windows, and back: a corner packing
// is exactly a 2 x 2 window torus holding every window once.
Tiling window_torus_of_corner_torus(const Tiling& corner);
Tiling corner_torus_of_window_torus(const Tiling& window);

// The window tori stored in tilesets/data/ (window-KxL-C-RxS.json, found by the solver; the file
// names the command that found it in "found_by") with K x L windows over C symbols, each checked
// by the validator. Throws std::logic_error for a stored file that is not a de Bruijn torus.
std::vector<Tiling> stored_window_tori(std::uint32_t colours, int window_rows, int window_cols);

// A de Bruijn torus without search: a stored one of this shape, or for 2 x 2 windows on the
// C^2 x C^2 torus the corner packing construct_packing() gives (constructions.hpp). `how` says
// which. nullopt when none is known.
struct ConstructedWindowTorus {
  Tiling tiling;
  std::string how;
};
std::optional<ConstructedWindowTorus> construct_window_torus(std::uint32_t colours, int window_rows, int window_cols,
                                                             int rows, int cols);

// The colour-quotient lift of window tori: A(i,j) = B(i mod R_B, j mod S_B) + m * E(i,j) with B a
// window torus over m symbols (R_B x S_B) and E one over k symbols whose sides are multiples of
// B's. A's window at (i,j) splits symbol by symbol into B's window at (i mod R_B, j mod S_B) (the
// symbols mod m) and E's window at (i,j) (the symbols div m), a bijection between windows over
// C = k*m symbols and pairs (m-window, k-window). When B holds every m-window exactly once, say
// w_B at cell p, the cells of A whose B-part is w_B are exactly the residue class of p modulo
// (R_B, S_B). Hence A holds every C-window exactly once if and only if, on each residue class of
// cells mod (R_B, S_B), E's windows are all k-windows exactly once; a class has
// (R/R_B)(S/S_B) cells, which must be k^(KL). (The 2 x 2 case is tilesets/construct_lift.cpp.)
// Throws InputError for mismatched windows or sizes.
Tiling window_colour_lift(const Tiling& base, const Tiling& quotient);

}  // namespace tilekit
