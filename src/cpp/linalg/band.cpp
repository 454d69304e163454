#include "linalg/band.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace rancf {

void band_matvec(const double* ab, const double* x, int n, int ku, double* out) {
  // by band rows (contiguous in ab), the diagonals of column offset j - i = ku - k in the order
  // of increasing j for every i: the same sums as row by row, without the stride n
  std::fill(out, out + n, 0.0);
  for (int k = 2 * ku; k >= 0; --k) {
    const int d = k - ku;  // i - j
    const double* row = ab + static_cast<std::ptrdiff_t>(k) * n;
    const int i0 = std::max(0, d), i1 = std::min(n, n + d);
    for (int i = i0; i < i1; ++i) out[i] += row[i - d] * x[i - d];
  }
}

BandLU::BandLU(int n, int ku)
    : n_(n),
      ku_(ku),
      ld_(3 * ku + 1),
      ab_(static_cast<std::size_t>(ld_) * static_cast<std::size_t>(n)),
      piv_(static_cast<std::size_t>(n)) {}

BandView BandLU::matrix() {
  std::fill(ab_.begin(), ab_.end(), 0.0);
  return {ab_.data(), 1, ld_, 2 * ku_};
}

bool BandLU::factor(const std::uint8_t* fixed) {
  const int n = n_, kv = 2 * ku_;
  double* a = ab_.data();
  auto at = [a, this, kv](int i, int j) -> double& {
    return a[static_cast<std::ptrdiff_t>(j) * ld_ + kv + i - j];
  };
  for (int i = 0; i < n; ++i) {
    if (!fixed[i]) continue;
    const int j0 = std::max(0, i - ku_), j1 = std::min(n, i + ku_ + 1);
    for (int j = j0; j < j1; ++j) {
      at(i, j) = 0.0;
      at(j, i) = 0.0;
    }
    at(i, i) = 1.0;
  }
  chol_ = symmetric() && factor_cholesky();
  return chol_ || factor_lu();
}

bool BandLU::symmetric() const {
  // |a_ij - a_ji| <= 1e-12 sqrt(|a_ii a_jj|), squared (no square root per entry)
  const int n = n_, kv = 2 * ku_;
  const double* a = ab_.data();
  for (int j = 0; j < n; ++j) {
    const double* col = a + static_cast<std::ptrdiff_t>(j) * ld_ + kv;  // col[p] = A(j + p, j)
    const int km = std::min(ku_, n - 1 - j);
    for (int p = 1; p <= km; ++p) {
      const double* cp = a + static_cast<std::ptrdiff_t>(j + p) * ld_ + kv;  // cp[-p] = A(j, j + p)
      const double d = col[p] - cp[-p];
      if (d * d > 1e-24 * std::abs(col[0] * cp[0])) return false;
    }
  }
  return true;
}

namespace {

// Columns j0 <= j < j1 of the band L D L^T, kd the half bandwidth (a compile-time constant for
// the common element bands: fully unrolled loops); col[p] = A(j + p, j), w = kd + 1 per column.
// Returns false at a pivot that is not positive.
template <int KD>
bool ldl_columns(double* l, int n, int kd_runtime, int j0, int j1) {
  const int kd = KD > 0 ? KD : kd_runtime, w = kd + 1;
  for (int j = j0; j < j1; ++j) {
    double* col = l + static_cast<std::ptrdiff_t>(j) * w;
    const double d = col[0];
    if (!(d > 0.0) || !std::isfinite(d)) return false;
    const double inv = 1.0 / d;
    const int km = KD > 0 ? KD : std::min(kd, n - 1 - j);
    for (int c = 1; c <= km; ++c) {  // A(j + r, j + c) -= A(j + r, j) A(j + c, j) / d
      double* cc = l + static_cast<std::ptrdiff_t>(j + c) * w - c;  // cc[r] = A(j + r, j + c)
      const double t = col[c] * inv;
      for (int r = c; r <= km; ++r) cc[r] -= col[r] * t;
    }
    col[0] = inv;
    for (int p = 1; p <= km; ++p) col[p] *= inv;
  }
  return true;
}

template <int KD>
bool ldl(double* l, int n) {  // the columns with a full band unrolled, the last kd generic
  const int full = std::max(0, n - KD);
  return ldl_columns<KD>(l, n, KD, 0, full) && ldl_columns<0>(l, n, KD, full, n);
}

// Solve L D L^T x = b in place with the factors of ldl (kd as there).
template <int KD>
void ldl_solve(const double* l, int n, int kd_runtime, double* x) {
  const int kd = KD > 0 ? KD : kd_runtime, w = kd + 1;
  for (int j = 0; j < n; ++j) {  // L y = b
    const double* col = l + static_cast<std::ptrdiff_t>(j) * w;
    const double bj = x[j];
    if (KD > 0 && j + KD < n) {
      for (int p = 1; p <= KD; ++p) x[j + p] -= col[p] * bj;
      continue;
    }
    const int km = std::min(kd, n - 1 - j);
    for (int p = 1; p <= km; ++p) x[j + p] -= col[p] * bj;
  }
  for (int j = n - 1; j >= 0; --j) {  // L^T x = D^-1 y
    const double* col = l + static_cast<std::ptrdiff_t>(j) * w;
    double s = x[j] * col[0];
    if (KD > 0 && j + KD < n) {
      for (int p = 1; p <= KD; ++p) s -= col[p] * x[j + p];
    } else {
      const int km = std::min(kd, n - 1 - j);
      for (int p = 1; p <= km; ++p) s -= col[p] * x[j + p];
    }
    x[j] = s;
  }
}

}  // namespace

bool BandLU::factor_cholesky() {
  // right-looking band L D L^T (no square roots) on the lower triangle, copied to l_ (ab_ stays
  // for the LU); a pivot that is not positive sends the matrix to the LU
  const int n = n_, kv = 2 * ku_, w = ku_ + 1;
  l_.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const double* col = ab_.data() + static_cast<std::ptrdiff_t>(j) * ld_ + kv;
    std::copy(col, col + w, l_.data() + static_cast<std::ptrdiff_t>(j) * w);
  }
  switch (ku_) {  // the planar cable's band, the spatial cable's and the rod's
    case 7:
      return ldl<7>(l_.data(), n);
    case 11:
      return ldl<11>(l_.data(), n);
    case 13:
      return ldl<13>(l_.data(), n);
    default:
      return ldl_columns<0>(l_.data(), n, ku_, 0, n);
  }
}

bool BandLU::factor_lu() {
  const int n = n_, kl = ku_, kv = 2 * ku_;
  double* a = ab_.data();
  auto at = [a, this, kv](int i, int j) -> double& {
    return a[static_cast<std::ptrdiff_t>(j) * ld_ + kv + i - j];
  };
  int ju = 0;  // last column touched by the U factor so far
  for (int j = 0; j < n; ++j) {
    const int km = std::min(kl, n - 1 - j);
    double* col = a + static_cast<std::ptrdiff_t>(j) * ld_ + kv;  // col[p] = A(j + p, j)
    int jp = 0;
    double best = std::abs(col[0]);
    for (int p = 1; p <= km; ++p)
      if (std::abs(col[p]) > best) best = std::abs(col[p]), jp = p;
    piv_[static_cast<std::size_t>(j)] = j + jp;
    if (!(best > 0.0) || !std::isfinite(best)) return false;
    ju = std::max(ju, std::min(j + ku_ + jp, n - 1));
    if (jp != 0)
      for (int c = j; c <= ju; ++c) std::swap(at(j, c), at(j + jp, c));
    const double inv = 1.0 / col[0];
    int lm = km;  // the column's last nonzero below the diagonal (a sparse band: fewer updates)
    while (lm > 0 && col[lm] == 0.0) --lm;
    for (int p = 1; p <= lm; ++p) col[p] *= inv;
    if (lm == 0) continue;
    for (int c = j + 1; c <= ju; ++c) {
      const double ujc = at(j, c);
      if (ujc == 0.0) continue;
      double* cc = a + static_cast<std::ptrdiff_t>(c) * ld_ + kv + j - c;  // cc[p] = A(j + p, c)
      for (int p = 1; p <= lm; ++p) cc[p] -= col[p] * ujc;
    }
  }
  return true;
}

void BandLU::solve(double* rhs, const std::uint8_t* fixed) const {
  const int n = n_, kl = ku_, kv = 2 * ku_;
  const double* a = ab_.data();
  for (int i = 0; i < n; ++i)
    if (fixed[i]) rhs[i] = 0.0;
  if (chol_) {
    switch (ku_) {
      case 7:
        return ldl_solve<7>(l_.data(), n, ku_, rhs);
      case 11:
        return ldl_solve<11>(l_.data(), n, ku_, rhs);
      case 13:
        return ldl_solve<13>(l_.data(), n, ku_, rhs);
      default:
        return ldl_solve<0>(l_.data(), n, ku_, rhs);
    }
  }
  for (int j = 0; j < n - 1; ++j) {  // L
    const int l = piv_[static_cast<std::size_t>(j)];
    if (l != j) std::swap(rhs[l], rhs[j]);
    const double bj = rhs[j];
    if (bj == 0.0) continue;
    const int lm = std::min(kl, n - 1 - j);
    const double* col = a + static_cast<std::ptrdiff_t>(j) * ld_ + kv;
    for (int p = 1; p <= lm; ++p) rhs[j + p] -= col[p] * bj;
  }
  for (int j = n - 1; j >= 0; --j) {                                    // U, bandwidth kl + ku
    const double* col = a + static_cast<std::ptrdiff_t>(j) * ld_ + kv;  // col[i - j] = U(i, j)
    rhs[j] /= col[0];
    const double bj = rhs[j];
    if (bj == 0.0) continue;
    const int i0 = std::max(0, j - kv);
    for (int i = i0; i < j; ++i) rhs[i] -= col[i - j] * bj;
  }
}

}  // namespace rancf
