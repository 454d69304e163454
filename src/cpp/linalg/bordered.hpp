// A block-diagonal band matrix bordered by a few sparse rows and columns
// (docs/derivations/systems.md section 4):
//
//   [ A  P ] [x]   [r]        A = diag(A_1, ..., A_k), band blocks (LU with partial pivoting)
//   [ Q  D ] [z] = [s]        P (n x p), Q (p x n) sparse; D (p x p) dense
//
// Schur complement on the border: W = A^-1 P (each column solved in the blocks it touches only),
// S = D - Q W (dense LU with partial pivoting), z = S^-1 (s - Q A^-1 r), x = A^-1 r - W z.
// Cost per factorization: the bands O(n b^2), p column solves, O(p^3): linear in the number of
// elements for a fixed border.  Held coordinates (supports) are rows and columns of the identity.
//
// Entries of A outside its blocks' bands (far entries: a pulley's couplings with a belt,
// self-contact of distant elements) come in apart (add_far); factor() places them (section 4
// of the derivation): a row or column with many of them (a rigid body coupled to a line)
// becomes one more border unknown (w = K_i. x: Q[w] = K_i., P[i][w] = 1, D = -1; or
// z = x_j: P[.][z] = K_.j, Q[z][j] = 1, D = -1), and the scattered rest either such unknowns as
// well or, where that is cheaper by the operation counts, goes into one band of all the blocks
// together after a reverse Cuthill-McKee ordering (A's pattern with those entries), factored as
// one band (BandLU).
#pragma once

#include <cstdint>
#include <vector>

#include "linalg/band.hpp"

namespace rancf {

class BorderedLU {
 public:
  /// An entry A[i][j] outside the blocks' bands (add_far).
  struct Far {
    int i, j;
    double v;
  };
  /// Blocks as (offset, size, half bandwidth), contiguous from 0; fixed (n): held coordinates.
  BorderedLU(const std::vector<int>& offsets, const std::vector<int>& sizes,
             const std::vector<int>& kus, const std::uint8_t* fixed);
  [[nodiscard]] int n() const { return n_; }
  [[nodiscard]] int blocks() const { return static_cast<int>(lu_.size()); }
  /// Block b's matrix (set to zero), in local indices.
  BandView block(int b);
  /// Block b's matrix as it is.
  BandView view(int b) { return lu_[static_cast<std::size_t>(b)].view(); }
  [[nodiscard]] int block_ku(int b) const { return lu_[static_cast<std::size_t>(b)].ku(); }
  [[nodiscard]] int block_of(int i) const;
  [[nodiscard]] int block_offset(int b) const { return off_[static_cast<std::size_t>(b)]; }
  /// Clear the border and size it for p extra unknowns.
  void reset_border(int p);
  void add_p(int col, int row, double v);  ///< P[row][col] += v
  void add_q(int row, int col, double v);  ///< Q[row][col] += v
  void add_d(int i, int j, double v);      ///< D[i][j] += v
  /// A[i][j] += v for an entry outside the blocks' bands (after reset_border).
  void add_far(int i, int j, double v) {
    if (v != 0.0) far_.push_back({i, j, v});
  }
  /// After reset_border: the far entries are those of `entries` (nonzero, any order), which
  /// gets the earlier ones (a swap: no copy, and both vectors keep their memory).
  void swap_far(std::vector<Far>& entries) { far_.swap(entries); }
  /// Factor the blocks and the Schur complement; false if singular.
  bool factor();
  /// Solve in place: x (n) holds r, z (p) holds s.
  void solve(double* x, double* z) const;
  /// The border's unknowns (without those factor() makes of far entries).
  [[nodiscard]] int border() const { return pu_; }
  /// Whether the last factor() put far entries into one reordered band.
  [[nodiscard]] bool merged() const { return merged_; }
  /// Before factor(): the dense matrix of x and the first `keep` border unknowns, the others
  /// (coupling unknowns with D = -I) eliminated: [A + P_z Q_z, P_k; Q_k, D_kk], row-major
  /// (n + keep)^2.  For checks and small eigenproblems.
  void dense(int keep, double* out);
  /// Before factor(): the nonzeros of [A P; Q D] (size n + p) as triplets (row, column, value),
  /// band entries of every block and the border's; for sparse eigenproblems.
  void triplets(std::vector<int>& rows, std::vector<int>& cols, std::vector<double>& vals);

 private:
  struct Entry {
    int index;
    double value;
  };
  void solve_blocks(double* x, const std::vector<char>* touched) const;
  /// Far entries into border unknowns or the merged band (class comment).
  void place_far();
  /// The reverse Cuthill-McKee order of A's pattern with the far entries `rest` into perm_ and
  /// pos_; returns the half bandwidth in that order.
  int order(const std::vector<Far>& rest);
  /// The merged band (half width kb): the blocks and the far entries `rest`, held coordinates
  /// in the new order.
  void fill_merged(const std::vector<Far>& rest, int kb);
  bool factor_schur();
  int n_ = 0, p_ = 0, pu_ = 0;  // border unknowns: all, the caller's
  std::vector<Far> far_;
  std::vector<int> rows_, cols_, count_, gid_, at_, idx_, keys_;  // place_far's work arrays
  std::vector<double> du_;                                        // the caller's D (pu x pu)
  bool merged_ = false;
  std::uint64_t sig_ = 0;    // place_far's choice for the far entries' pattern sig_: (a), (b) or
  int choice_ = 0, kb_ = 0;  // (c) as 0, 1, 2, and the merged band's half width
  std::vector<int> perm_, pos_;       // merged: new -> old and old -> new index
  std::vector<std::uint8_t> mfixed_;  // merged: held coordinates in the new order
  BandLU big_{0, 0};                  // merged: the band of all blocks
  mutable std::vector<double> mx_;    // merged: solve's work array
  std::vector<int> off_, size_;
  std::vector<BandLU> lu_;
  std::vector<std::vector<std::uint8_t>> fixed_;
  // P's columns and Q's rows (the first p_ of them count; more are kept for their memory)
  std::vector<std::vector<Entry>> pcol_, qrow_;
  std::vector<double> d_, w_, s_;  // D (p x p), W (n x p, column-major), Schur LU (p x p)
  std::vector<int> wlo_, whi_;     // rows [lo, hi) of W's column c that can be nonzero
  std::vector<int> piv_;
  mutable std::vector<double> rhs_;  // solve's work array
};

}  // namespace rancf
