#include "band.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace rancf {

void band_matvec(const double* ab, const double* x, int n, int ku, double* out) {
  for (int i = 0; i < n; ++i) {
    double s = 0.0;
    const int j0 = std::max(0, i - ku), j1 = std::min(n, i + ku + 1);
    for (int j = j0; j < j1; ++j) s += ab[static_cast<std::ptrdiff_t>(ku + i - j) * n + j] * x[j];
    out[i] = s;
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
  const int n = n_, kl = ku_, kv = 2 * ku_;
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
    for (int p = 1; p <= km; ++p) col[p] *= inv;
    for (int c = j + 1; c <= ju; ++c) {
      const double ujc = at(j, c);
      if (ujc == 0.0) continue;
      double* cc = a + static_cast<std::ptrdiff_t>(c) * ld_ + kv + j - c;  // cc[p] = A(j + p, c)
      for (int p = 1; p <= km; ++p) cc[p] -= col[p] * ujc;
    }
  }
  return true;
}

void BandLU::solve(double* rhs, const std::uint8_t* fixed) const {
  const int n = n_, kl = ku_, kv = 2 * ku_;
  const double* a = ab_.data();
  for (int i = 0; i < n; ++i)
    if (fixed[i]) rhs[i] = 0.0;
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
