#pragma once
// Minimum-error boundary cuts (Efros & Freeman 2001, the cut Cohen et al. 2003 use to join the
// samples of a Wang tile): a path through a band of overlapping pixels of two samples A and B,
// one position per row, that minimises the summed error |A - B| along it. Pixels on one side of
// the path come from A, on the other side from B. Dynamic programming over the rows.
#include <vector>

namespace tilekit {

struct CutBand {
  int rows = 0, width = 0;  // positions 0..width-1 in every row
  std::vector<int> lo, hi;  // allowed positions of row r: lo[r]..hi[r] (inclusive)
  std::vector<float> cost;  // error of the path at position p of row r: cost[r * width + p]
  // Consecutive positions differ by exactly one (a cut along the pixel diagonal, where the
  // band's rows are anti-diagonals), else by at most one (a cut along a pixel row or column).
  bool diagonal = false;
  // Optional (empty, or rows x width): what a step of the path costs where it moves between rows
  // r - 1 and r (not with `diagonal`): into position p from p - 1 (rise) or from p + 1 (fall). A
  // cut along pixel columns that moves leaves one pair of vertical neighbours from different
  // samples, whose step shows like the steps across the path.
  std::vector<float> rise, fall;
  float& at(int r, int p) { return cost[std::size_t(r) * std::size_t(width) + std::size_t(p)]; }
};

struct CutPath {
  std::vector<int> pos;  // position per row
  double cost = 0;       // summed error along the path
};

// The cheapest path; ties go to the position nearest the band's middle, then the lower one.
// The band must admit a path (asserted).
CutPath min_error_cut(const CutBand& band);

}  // namespace tilekit
