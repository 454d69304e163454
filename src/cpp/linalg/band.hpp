// Band matrices: views on band storage, products, and the band solver: Cholesky (L L^T) when
// the matrix is symmetric positive definite, else LU with partial pivoting.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rancf {

/// A square band matrix stored as A(i, j) = data[(off + i - j) * rs + j * cs].
struct BandView {
  double* data;
  std::ptrdiff_t rs;  ///< stride between band rows
  std::ptrdiff_t cs;  ///< stride between columns
  int off;            ///< storage row of the diagonal
  double& at(int i, int j) const { return data[(off + i - j) * rs + j * cs]; }
};

/// A band is split in two halves from n >= kSplitBands (ku + 1) unknowns (BandLU).
inline constexpr int kSplitBands = 64;
/// The smallest pivot a half of a split LU takes, relative to its column's largest entry.
inline constexpr double kSplitPivot = 0.1;

/// View on NumPy's (2 ku + 1, n) C-order band storage (LAPACK general band, kl = ku).
inline BandView numpy_band(double* ab, int n, int ku) { return {ab, n, 1, ku}; }

/// out = A x for a (2 ku + 1, n) C-order band matrix.
void band_matvec(const double* ab, const double* x, int n, int ku, double* out);

/// Factorization of a band matrix with kl = ku.  A symmetric matrix (to round-off: |a_ij - a_ji|
/// <= 1e-12 sqrt(|a_ii a_jj|)) is first factored as L D L^T from its lower triangle (the band
/// Cholesky of LAPACK dpbtf2 without its square roots: a quarter of the LU's work); if a pivot
/// is not positive (an indefinite matrix) or the matrix is not symmetric, LU with partial
/// pivoting (LAPACK dgbtf2 / dgbtrs).
/// Column-major storage with leading dimension 3 ku + 1; the diagonal sits at row 2 ku.
///
/// A large band (n >= kSplitBands (ku + 1)) is factored in two halves and a separator
/// (docs/derivations/systems.md section 6): the ku unknowns [m, m + ku) in its middle split it
/// into a top block, eliminated from its first column down, and a bottom block, eliminated
/// from its last column up, each leaving its Schur complement on the separator; their sum with
/// the separator's own entries is factored as a small dense matrix.  The two halves are
/// independent (on two threads when the element loops have them, bodies/threads.hpp), and
/// their arithmetic does not depend on the thread that runs them: the factors and solutions
/// are the same bit for bit on one thread or two.  The LU's pivots are searched in the half's
/// own rows and taken when at least kSplitPivot times the column's largest entry (the
/// separator's rows included); else the whole band is factored as one.
class BandLU {
 public:
  BandLU(int n, int ku);
  /// The matrix to factor, set to zero (fill-in rows included).
  BandView matrix();
  /// The matrix as it is (to add to it after matrix()).
  BandView view() { return {ab_.data(), 1, ld_, 2 * ku_}; }
  /// Rows and columns of the held coordinates replaced by the identity, then factored (the
  /// LU in place).  Returns false for an exactly singular matrix.
  bool factor(const std::uint8_t* fixed);
  /// Solve in place with the factors (rhs[fixed] set to zero first).
  void solve(double* rhs, const std::uint8_t* fixed) const;
  [[nodiscard]] int n() const { return n_; }
  [[nodiscard]] int ku() const { return ku_; }
  /// Whether the last factorization was the Cholesky one.
  [[nodiscard]] bool cholesky() const { return chol_; }
  /// Whether a large band may be split (the default; false: always one band, for checks).
  void set_split(bool allowed) { allow_split_ = allowed; }
  /// Whether the last factorization was split in two halves (class comment).
  [[nodiscard]] bool split() const { return split_ > 0; }

  /// One half of a split band (class comment): its own band of the block's unknowns and the
  /// separator's, in the top half's order or reversed (the bottom's), `e` columns eliminated.
  struct Half {
    int n = 0, e = 0;
    bool reversed = false;
    std::vector<double> a;  // L D L^T: the lower band (ku + 1 a column); LU: as ab_
    std::vector<int> piv;
    mutable std::vector<double> w;  // solve's work vector (n)
  };

 private:
  bool symmetric() const;
  bool factor_cholesky();
  bool factor_lu();
  bool factor_split(bool ldl);
  bool factor_separator(bool ldl);
  void solve_split(double* rhs) const;
  void half_factor(int h, bool ldl);

 public:  // the passes of a split solve (its chunks, band.cpp)
  /// Half h's forward pass: its block of rhs into its work vector, the separator's updates.
  void half_forward(int h, const double* rhs) const;
  /// The separator's solution (after both forward passes).
  void solve_separator(double* rhs) const;
  /// Half h's backward pass, its block of rhs (after the separator's solution).
  void half_backward(int h, double* rhs) const;

 private:
  int n_, ku_, ld_;
  bool chol_ = false;
  bool allow_split_ = true;
  int split_ = 0;          // the separator's first unknown m (0: not split)
  Half half_[2];           // the top and the bottom half
  bool half_ok_[2] = {};   // each half's elimination found its pivots
  std::vector<double> s_;  // the separator's matrix, then its dense factors (ku x ku)
  std::vector<int> spiv_;
  mutable std::vector<double> sr_;  // the separator's right-hand side
  std::vector<double> ab_;
  std::vector<double> l_;  // L D L^T: L(j + p, j) at l_[j (ku + 1) + p], 1 / D(j) at p = 0  //
                           // Cholesky: L(j + p, j) at l_[j (ku + 1) + p], 1 / L(j, j) at p = 0
  std::vector<int> piv_;
};

}  // namespace rancf
