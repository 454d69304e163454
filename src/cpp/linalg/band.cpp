#include "linalg/band.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>
#include <utility>

#include "bodies/threads.hpp"

namespace rancf {

namespace {

// Rows [i0, i1) of out = A x (band_matvec).
void band_matvec_rows(const double* ab, const double* x, int n, int ku, int i0, int i1,
                      double* out) {
  // by band rows (contiguous in ab), the diagonals of column offset j - i = ku - k in the order
  // of increasing j for every i: the same sums as row by row, without the stride n
  std::fill(out + i0, out + i1, 0.0);
  for (int k = 2 * ku; k >= 0; --k) {
    const int d = k - ku;  // i - j
    const double* row = ab + static_cast<std::ptrdiff_t>(k) * n;
    const int a = std::max(i0, d), b = std::min(i1, n + d);
    for (int i = a; i < b; ++i) out[i] += row[i - d] * x[i - d];
  }
}

struct Matvec {
  const double* ab;
  const double* x;
  int n, ku;
  double* out;
};

void matvec_chunk(void* ctx, int c) {
  const Matvec& m = *static_cast<const Matvec*>(ctx);
  const int half = m.n / 2;
  band_matvec_rows(m.ab, m.x, m.n, m.ku, c == 0 ? 0 : half, c == 0 ? half : m.n, m.out);
}

}  // namespace

void band_matvec(const double* ab, const double* x, int n, int ku, double* out) {
  // a large band's two halves of rows on two threads where the pool has them: every row's sum
  // is the same whichever thread computes it
  Matvec job{ab, x, n, ku, out};
  if (n < kSplitBands * (ku + 1) || !run_chunks(2, matvec_chunk, &job))
    band_matvec_rows(ab, x, n, ku, 0, n, out);
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
  split_ = 0;
  const bool sym = symmetric();
  if (allow_split_ && n >= kSplitBands * (ku_ + 1)) {  // two halves and a separator (class comment)
    chol_ = sym && factor_split(true);
    if (chol_ || factor_split(false)) return true;
  }
  chol_ = sym && factor_cholesky();
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

// L y = b over the columns [j0, j1) of the factors of ldl (kd as there), in place.
template <int KD>
void ldl_forward(const double* l, int n, int kd_runtime, int j0, int j1, double* x) {
  const int kd = KD > 0 ? KD : kd_runtime, w = kd + 1;
  for (int j = j0; j < j1; ++j) {
    const double* col = l + static_cast<std::ptrdiff_t>(j) * w;
    const double bj = x[j];
    if (KD > 0 && j + KD < n) {
      for (int p = 1; p <= KD; ++p) x[j + p] -= col[p] * bj;
      continue;
    }
    const int km = std::min(kd, n - 1 - j);
    for (int p = 1; p <= km; ++p) x[j + p] -= col[p] * bj;
  }
}

// L^T x = D^-1 y over the columns j1 - 1 down to j0, in place (x beyond j1 - 1 known).
template <int KD>
void ldl_backward(const double* l, int n, int kd_runtime, int j0, int j1, double* x) {
  const int kd = KD > 0 ? KD : kd_runtime, w = kd + 1;
  for (int j = j1 - 1; j >= j0; --j) {
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

// Solve L D L^T x = b in place with the factors of ldl (kd as there), or, with e < n, only
// the first e columns: the forward pass (the rows beyond e get their updates) when `forward`,
// else the backward pass (the rows beyond e known).
template <int KD>
void ldl_pass(const double* l, int n, int kd, int e, bool forward, double* x) {
  if (forward)
    ldl_forward<KD>(l, n, kd, 0, e, x);
  else
    ldl_backward<KD>(l, n, kd, 0, e, x);
}

void ldl_dispatch(const double* l, int n, int kd, int e, bool forward, double* x) {
  switch (kd) {
    case 7:
      return ldl_pass<7>(l, n, kd, e, forward, x);
    case 11:
      return ldl_pass<11>(l, n, kd, e, forward, x);
    case 13:
      return ldl_pass<13>(l, n, kd, e, forward, x);
    default:
      return ldl_pass<0>(l, n, kd, e, forward, x);
  }
}

// The band L D L^T's first e columns (all of them: e = n); false at a pivot not positive.
bool ldl_dispatch_factor(double* l, int n, int kd, int e) {
  switch (kd) {  // the planar cable's band, the spatial cable's and the rod's
    case 7:
      return e == n ? ldl<7>(l, n) : ldl_columns<7>(l, n, kd, 0, e);
    case 11:
      return e == n ? ldl<11>(l, n) : ldl_columns<11>(l, n, kd, 0, e);
    case 13:
      return e == n ? ldl<13>(l, n) : ldl_columns<13>(l, n, kd, 0, e);
    default:
      return ldl_columns<0>(l, n, kd, 0, e);
  }
}

// LU with partial pivoting (LAPACK dgbtf2) of the first e columns of an n x n band (half
// width ku, column-major, leading dimension ld, the diagonal at row 2 ku); with e < n the rows
// beyond e get their updates (a Schur complement) and the pivots are searched in the rows
// before e, taken when at least kSplitPivot times the column's largest entry.  0: factored;
// 1: singular; 2: a pivot below that bound.
int lu_columns(double* a, int ld, int n, int ku, int e, int* piv) {
  const int kv = 2 * ku;
  auto at = [a, ld, kv](int i, int j) -> double& {
    return a[static_cast<std::ptrdiff_t>(j) * ld + kv + i - j];
  };
  int ju = 0;  // last column touched by the U factor so far
  for (int j = 0; j < e; ++j) {
    const int km = std::min(ku, n - 1 - j), kp = std::min(km, e - 1 - j);
    double* col = a + static_cast<std::ptrdiff_t>(j) * ld + kv;  // col[p] = A(j + p, j)
    int jp = 0;
    double best = std::abs(col[0]);
    for (int p = 1; p <= kp; ++p)
      if (std::abs(col[p]) > best) best = std::abs(col[p]), jp = p;
    piv[j] = j + jp;
    if (!(best > 0.0) || !std::isfinite(best)) return 1;
    for (int p = kp + 1; p <= km; ++p)
      if (!(best >= kSplitPivot * std::abs(col[p]))) return 2;
    ju = std::max(ju, std::min(j + ku + jp, n - 1));
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
      double* cc = a + static_cast<std::ptrdiff_t>(c) * ld + kv + j - c;  // cc[p] = A(j + p, c)
      for (int p = 1; p <= lm; ++p) cc[p] -= col[p] * ujc;
    }
  }
  return 0;
}

// L y = b with the factors of lu_columns, its first e columns (the rows beyond get updates).
void lu_forward(const double* a, int ld, int n, int ku, int e, const int* piv, double* x) {
  const int kv = 2 * ku;
  for (int j = 0; j < std::min(e, n - 1); ++j) {
    const int l = piv[j];
    if (l != j) std::swap(x[l], x[j]);
    const double bj = x[j];
    if (bj == 0.0) continue;
    const int lm = std::min(ku, n - 1 - j);
    const double* col = a + static_cast<std::ptrdiff_t>(j) * ld + kv;
    for (int p = 1; p <= lm; ++p) x[j + p] -= col[p] * bj;
  }
}

// U x = y with the factors of lu_columns, its first e rows (x beyond e known), in place.
void lu_backward(const double* a, int ld, int n, int ku, int e, double* x) {
  const int kv = 2 * ku;
  for (int j = n - 1; j >= 0; --j) {                                   // U, bandwidth 2 ku
    const double* col = a + static_cast<std::ptrdiff_t>(j) * ld + kv;  // col[i - j] = U(i, j)
    if (j < e) x[j] /= col[0];
    const double bj = x[j];
    if (bj == 0.0) continue;
    const int i0 = std::max(0, j - kv), i1 = std::min(j, e);
    for (int i = i0; i < i1; ++i) x[i] -= col[i - j] * bj;
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
  return ldl_dispatch_factor(l_.data(), n, ku_, n);
}

bool BandLU::factor_lu() { return lu_columns(ab_.data(), ld_, n_, ku_, n_, piv_.data()) == 0; }

void BandLU::solve(double* rhs, const std::uint8_t* fixed) const {
  for (int i = 0; i < n_; ++i)
    if (fixed[i]) rhs[i] = 0.0;
  if (split_ > 0) return solve_split(rhs);
  if (chol_) {
    ldl_dispatch(l_.data(), n_, ku_, n_, true, rhs);
    return ldl_dispatch(l_.data(), n_, ku_, n_, false, rhs);
  }
  lu_forward(ab_.data(), ld_, n_, ku_, n_, piv_.data(), rhs);
  lu_backward(ab_.data(), ld_, n_, ku_, n_, rhs);
}

// ---- the split band (class comment of BandLU; docs/derivations/systems.md section 6) ----

namespace {

/// Run f(0) and f(1), on two threads where the pool has them (bodies/threads.hpp).
template <class F>
void run_two(F& f) {
  auto job = [](void* ctx, int c) { (*static_cast<F*>(ctx))(c); };
  if (!run_chunks(2, job, &f)) {
    f(0);
    f(1);
  }
}

}  // namespace

bool BandLU::factor_split(bool ldl) {
  const int n = n_, k = ku_, m = (n - k) / 2;
  half_[0].n = m + k;
  half_[0].e = m;
  half_[0].reversed = false;
  half_[1].n = n - m;
  half_[1].e = n - m - k;
  half_[1].reversed = true;
  split_ = m;
  auto job = [this, ldl](int h) { half_factor(h, ldl); };
  run_two(job);
  if (!half_ok_[0] || !half_ok_[1] || !factor_separator(ldl)) {
    split_ = 0;
    return false;
  }
  return true;
}

void BandLU::half_factor(int h, bool ldl) {
  // the half's band copied column by column (a column of the reversed half is one of A read
  // from its end), without the separator's own entries (its Schur complement only)
  Half& H = half_[h];
  const int n = n_, k = ku_, kv = 2 * ku_, hn = H.n, e = H.e;
  const bool rev = H.reversed;
  auto column = [this, kv](int j) {
    return ab_.data() + static_cast<std::ptrdiff_t>(j) * ld_ + kv;
  };
  if (ldl) {  // the lower band, read from the lower triangle of A in either order
    const int w = k + 1;
    H.a.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(hn));
    std::fill(H.a.begin() + static_cast<std::ptrdiff_t>(e) * w, H.a.end(), 0.0);
    for (int c = 0; c < e; ++c) {
      double* dst = H.a.data() + static_cast<std::ptrdiff_t>(c) * w;  // dst[p] = A'(c + p, c)
      const int pm = std::min(k, hn - 1 - c);
      if (!rev) {
        std::copy(column(c), column(c) + pm + 1, dst);
        continue;
      }
      const int gc = n - 1 - c;  // A'(c + p, c) = A(gc, gc - p), row gc of column gc - p
      for (int p = 0; p <= pm; ++p) dst[p] = column(gc - p)[p];
    }
    half_ok_[h] = ldl_dispatch_factor(H.a.data(), hn, k, e);
    return;
  }
  H.a.assign(static_cast<std::size_t>(ld_) * static_cast<std::size_t>(hn), 0.0);
  H.piv.resize(static_cast<std::size_t>(hn));
  for (int c = 0; c < hn; ++c) {
    double* dst = H.a.data() + static_cast<std::ptrdiff_t>(c) * ld_ + kv;  // dst[r - c]
    const int r0 = std::max(0, c - k), r1 = std::min(c < e ? hn : e, c + k + 1);
    const double* src = column(rev ? n - 1 - c : c);  // src[i - j] = A(i, j)
    for (int r = r0; r < r1; ++r) dst[r - c] = src[rev ? c - r : r - c];
  }
  half_ok_[h] = lu_columns(H.a.data(), ld_, hn, k, e, H.piv.data()) == 0;
}

bool BandLU::factor_separator(bool ldl) {
  // S = A_ss + (the top half's Schur complement) + (the bottom's), dense k x k, row-major
  const int n = n_, k = ku_, m = split_, kv = 2 * ku_, w = k + 1;
  const Half &t = half_[0], &b = half_[1];
  s_.assign(static_cast<std::size_t>(k * k), 0.0);
  auto S = [this, k](int i, int j) -> double& { return s_[static_cast<std::size_t>(i * k + j)]; };
  auto A = [this, kv](int i, int j) { return ab_[static_cast<std::size_t>(j * ld_ + kv + i - j)]; };
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < (ldl ? i + 1 : k); ++j) {
      const int bi = n - 1 - m - i, bj = n - 1 - m - j;  // the bottom half's local indices
      if (ldl)  // lower triangles: (m + i, m + j) on top, (bj, bi) reversed below
        S(i, j) = (A(m + i, m + j) + t.a[static_cast<std::size_t>((m + j) * w + i - j)]) +
                  b.a[static_cast<std::size_t>(bi * w + i - j)];
      else
        S(i, j) = (A(m + i, m + j) + t.a[static_cast<std::size_t>((m + j) * ld_ + kv + i - j)]) +
                  b.a[static_cast<std::size_t>(bj * ld_ + kv + bi - bj)];
    }
  if (ldl) {  // dense L D L^T as ldl_columns: 1 / D(j) on the diagonal, L below
    for (int j = 0; j < k; ++j) {
      const double d = S(j, j);
      if (!(d > 0.0) || !std::isfinite(d)) return false;
      const double inv = 1.0 / d;
      for (int c = j + 1; c < k; ++c) {
        const double f = S(c, j) * inv;
        for (int r = c; r < k; ++r) S(r, c) -= S(r, j) * f;
      }
      S(j, j) = inv;
      for (int r = j + 1; r < k; ++r) S(r, j) *= inv;
    }
    return true;
  }
  spiv_.resize(static_cast<std::size_t>(k));  // dense LU with partial pivoting
  for (int j = 0; j < k; ++j) {
    int pv = j;
    for (int i = j + 1; i < k; ++i)
      if (std::abs(S(i, j)) > std::abs(S(pv, j))) pv = i;
    spiv_[static_cast<std::size_t>(j)] = pv;
    const double best = std::abs(S(pv, j));
    if (!(best > 0.0) || !std::isfinite(best)) return false;
    if (pv != j)
      for (int c = 0; c < k; ++c) std::swap(S(j, c), S(pv, c));
    const double inv = 1.0 / S(j, j);
    for (int i = j + 1; i < k; ++i) {
      const double l = S(i, j) * inv;
      S(i, j) = l;
      for (int c = j + 1; c < k; ++c) S(i, c) -= l * S(j, c);
    }
  }
  return true;
}

void BandLU::half_forward(int h, const double* rhs) const {
  const Half& H = half_[h];
  const int n = n_;
  H.w.assign(static_cast<std::size_t>(H.n), 0.0);  // the separator's rows: its updates only
  for (int r = 0; r < H.e; ++r) H.w[static_cast<std::size_t>(r)] = rhs[H.reversed ? n - 1 - r : r];
  if (chol_)
    ldl_dispatch(H.a.data(), H.n, ku_, H.e, true, H.w.data());
  else
    lu_forward(H.a.data(), ld_, H.n, ku_, H.e, H.piv.data(), H.w.data());
}

void BandLU::half_backward(int h, double* rhs) const {
  const Half& H = half_[h];
  const int n = n_, k = ku_, m = split_;
  for (int a = 0; a < k; ++a)  // the separator's solution
    H.w[static_cast<std::size_t>(H.reversed ? n - 1 - m - a : m + a)] =
        sr_[static_cast<std::size_t>(a)];
  if (chol_)
    ldl_dispatch(H.a.data(), H.n, k, H.e, false, H.w.data());
  else
    lu_backward(H.a.data(), ld_, H.n, k, H.e, H.w.data());
  for (int r = 0; r < H.e; ++r) rhs[H.reversed ? n - 1 - r : r] = H.w[static_cast<std::size_t>(r)];
}

void BandLU::solve_separator(double* rhs) const {
  // z = S^-1 (r_s + the two halves' updates), with S's dense factors (factor_separator)
  const int n = n_, k = ku_, m = split_;
  sr_.resize(static_cast<std::size_t>(k));
  std::vector<double>& z = sr_;
  for (int a = 0; a < k; ++a)
    z[static_cast<std::size_t>(a)] = (rhs[m + a] + half_[0].w[static_cast<std::size_t>(m + a)]) +
                                     half_[1].w[static_cast<std::size_t>(n - 1 - m - a)];
  auto S = [this, k](int i, int j) { return s_[static_cast<std::size_t>(i * k + j)]; };
  auto Z = [&z](int i) -> double& { return z[static_cast<std::size_t>(i)]; };
  if (chol_) {
    for (int j = 0; j < k; ++j)
      for (int p = j + 1; p < k; ++p) Z(p) -= S(p, j) * Z(j);
    for (int j = k - 1; j >= 0; --j) {
      double v = Z(j) * S(j, j);
      for (int p = j + 1; p < k; ++p) v -= S(p, j) * Z(p);
      Z(j) = v;
    }
  } else {
    for (int j = 0; j < k; ++j) std::swap(Z(j), Z(spiv_[static_cast<std::size_t>(j)]));
    for (int i = 1; i < k; ++i)
      for (int j = 0; j < i; ++j) Z(i) -= S(i, j) * Z(j);
    for (int i = k - 1; i >= 0; --i) {
      for (int j = i + 1; j < k; ++j) Z(i) -= S(i, j) * Z(j);
      Z(i) /= S(i, i);
    }
  }
}

namespace {

/// A split solve as one loop of two chunks (bodies/threads.hpp): chunk 1 the bottom half's
/// forward and backward passes, chunk 0 the top half's and, between them, the separator's
/// once the bottom's forward pass is done.  Chunk 0 takes chunk 1 over if no worker has
/// claimed it by the end of its own forward pass: it never waits for a chunk nobody runs.
struct SplitSolve {
  const BandLU* lu;
  double* rhs;
  std::atomic<int> claimed{0}, forward{0}, separator{0};

  static void wait(const std::atomic<int>& flag) {
    while (flag.load(std::memory_order_acquire) == 0) std::this_thread::yield();
  }

  void chunk(int c) {
    if (c == 1) {
      if (claimed.exchange(1) != 0) return;  // taken over by chunk 0
      lu->half_forward(1, rhs);
      forward.store(1, std::memory_order_release);
      wait(separator);
      lu->half_backward(1, rhs);
      return;
    }
    lu->half_forward(0, rhs);
    const bool alone = claimed.exchange(1) == 0;
    if (alone)
      lu->half_forward(1, rhs);
    else
      wait(forward);
    lu->solve_separator(rhs);
    separator.store(1, std::memory_order_release);
    lu->half_backward(0, rhs);
    if (alone) lu->half_backward(1, rhs);
  }
};

void split_solve_chunk(void* ctx, int c) { static_cast<SplitSolve*>(ctx)->chunk(c); }

}  // namespace

void BandLU::solve_split(double* rhs) const {
  SplitSolve job{this, rhs};
  if (!run_chunks(2, split_solve_chunk, &job)) job.chunk(0);
  for (int a = 0; a < ku_; ++a) rhs[split_ + a] = sr_[static_cast<std::size_t>(a)];
}

}  // namespace rancf
