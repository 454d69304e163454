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

 private:
  bool symmetric() const;
  bool factor_cholesky();
  bool factor_lu();
  int n_, ku_, ld_;
  bool chol_ = false;
  std::vector<double> ab_;
  std::vector<double> l_;  // L D L^T: L(j + p, j) at l_[j (ku + 1) + p], 1 / D(j) at p = 0  //
                           // Cholesky: L(j + p, j) at l_[j (ku + 1) + p], 1 / L(j, j) at p = 0
  std::vector<int> piv_;
};

}  // namespace rancf
