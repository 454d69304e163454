#include "linalg/bordered.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace rancf {

namespace {
std::size_t sz(int i) { return static_cast<std::size_t>(i); }
}  // namespace

BorderedLU::BorderedLU(const std::vector<int>& offsets, const std::vector<int>& sizes,
                       const std::vector<int>& kus, const std::uint8_t* fixed)
    : off_(offsets), size_(sizes) {
  for (std::size_t b = 0; b < sizes.size(); ++b) {
    lu_.emplace_back(sizes[b], kus[b]);
    fixed_.emplace_back(fixed + offsets[b], fixed + offsets[b] + sizes[b]);
    n_ += sizes[b];
  }
}

BandView BorderedLU::block(int b) { return lu_[sz(b)].matrix(); }

int BorderedLU::block_of(int i) const {
  const auto it = std::upper_bound(off_.begin(), off_.end(), i);
  return static_cast<int>(it - off_.begin()) - 1;
}

void BorderedLU::reset_border(int p) {
  p_ = p;
  pcol_.assign(sz(p), {});
  qrow_.assign(sz(p), {});
  d_.assign(sz(p * p), 0.0);
}

void BorderedLU::add_p(int col, int row, double v) {
  if (v != 0.0) pcol_[sz(col)].push_back({row, v});
}
void BorderedLU::add_q(int row, int col, double v) {
  if (v != 0.0) qrow_[sz(row)].push_back({col, v});
}
void BorderedLU::add_d(int i, int j, double v) { d_[sz(i * p_ + j)] += v; }

void BorderedLU::dense(int keep, double* out) {
  const int w = n_ + keep;
  std::fill(out, out + sz(w) * sz(w), 0.0);
  for (std::size_t b = 0; b < lu_.size(); ++b) {
    const BandView v = lu_[b].view();
    const int o = off_[b], nb = size_[b], ku = lu_[b].ku();
    for (int i = 0; i < nb; ++i)
      for (int j = std::max(0, i - ku); j < std::min(nb, i + ku + 1); ++j)
        out[sz(o + i) * sz(w) + sz(o + j)] = v.at(i, j);
  }
  for (int c = 0; c < p_; ++c) {
    if (c < keep) {
      for (const Entry& e : pcol_[sz(c)]) out[sz(e.index) * sz(w) + sz(n_ + c)] += e.value;
      for (const Entry& e : qrow_[sz(c)]) out[sz(n_ + c) * sz(w) + sz(e.index)] += e.value;
      for (int d = 0; d < keep; ++d) out[sz(n_ + c) * sz(w) + sz(n_ + d)] += d_[sz(c * p_ + d)];
    } else {  // z_c = Q_c x: A += P_c Q_c
      for (const Entry& pe : pcol_[sz(c)])
        for (const Entry& qe : qrow_[sz(c)])
          out[sz(pe.index) * sz(w) + sz(qe.index)] += pe.value * qe.value;
    }
  }
}

void BorderedLU::triplets(std::vector<int>& rows, std::vector<int>& cols,
                          std::vector<double>& vals) {
  auto put = [&](int i, int j, double v) {
    if (v == 0.0) return;
    rows.push_back(i);
    cols.push_back(j);
    vals.push_back(v);
  };
  for (std::size_t b = 0; b < lu_.size(); ++b) {
    const BandView v = lu_[b].view();
    const int o = off_[b], nb = size_[b], ku = lu_[b].ku();
    for (int i = 0; i < nb; ++i)
      for (int j = std::max(0, i - ku); j < std::min(nb, i + ku + 1); ++j)
        put(o + i, o + j, v.at(i, j));
  }
  for (int c = 0; c < p_; ++c) {
    for (const Entry& e : pcol_[sz(c)]) put(e.index, n_ + c, e.value);
    for (const Entry& e : qrow_[sz(c)]) put(n_ + c, e.index, e.value);
    for (int d = 0; d < p_; ++d) put(n_ + c, n_ + d, d_[sz(c * p_ + d)]);
  }
}

void BorderedLU::solve_blocks(double* x, const std::vector<char>* touched) const {
  for (std::size_t b = 0; b < lu_.size(); ++b) {
    if (touched != nullptr && !(*touched)[b]) continue;  // zero there already
    lu_[b].solve(x + off_[b], fixed_[b].data());
  }
}

bool BorderedLU::factor() {
  for (std::size_t b = 0; b < lu_.size(); ++b)
    if (!lu_[b].factor(fixed_[b].data())) return false;
  if (p_ == 0) return true;
  w_.resize(sz(n_) * sz(p_));
  wlo_.assign(sz(p_), n_);
  whi_.assign(sz(p_), 0);
  std::vector<char> touched(lu_.size());
  for (int c = 0; c < p_; ++c) {  // only the blocks the column touches: the rest stays zero
    double* col = w_.data() + sz(c) * sz(n_);
    std::fill(touched.begin(), touched.end(), 0);
    for (const Entry& e : pcol_[sz(c)]) touched[sz(block_of(e.index))] = 1;
    for (std::size_t b = 0; b < lu_.size(); ++b)
      if (touched[b]) {
        std::fill(col + off_[b], col + off_[b] + size_[b], 0.0);
        wlo_[sz(c)] = std::min(wlo_[sz(c)], off_[b]);
        whi_[sz(c)] = std::max(whi_[sz(c)], off_[b] + size_[b]);
      }
    for (const Entry& e : pcol_[sz(c)]) col[e.index] += e.value;
    solve_blocks(col, &touched);
  }
  s_ = d_;  // S = D - Q W
  for (int r = 0; r < p_; ++r)
    for (const Entry& e : qrow_[sz(r)])
      for (int c = 0; c < p_; ++c)
        if (e.index >= wlo_[sz(c)] && e.index < whi_[sz(c)])
          s_[sz(r * p_ + c)] -= e.value * w_[sz(c) * sz(n_) + sz(e.index)];
  piv_.resize(sz(p_));  // dense LU with partial pivoting, row-major
  for (int k = 0; k < p_; ++k) {
    int piv = k;
    double best = std::abs(s_[sz(k * p_ + k)]);
    for (int i = k + 1; i < p_; ++i)
      if (std::abs(s_[sz(i * p_ + k)]) > best) {
        best = std::abs(s_[sz(i * p_ + k)]);
        piv = i;
      }
    piv_[sz(k)] = piv;
    if (!(best > 0.0) || !std::isfinite(best)) return false;
    if (piv != k)
      for (int j = 0; j < p_; ++j) std::swap(s_[sz(k * p_ + j)], s_[sz(piv * p_ + j)]);
    const double inv = 1.0 / s_[sz(k * p_ + k)];
    for (int i = k + 1; i < p_; ++i) {
      const double l = s_[sz(i * p_ + k)] * inv;
      s_[sz(i * p_ + k)] = l;
      for (int j = k + 1; j < p_; ++j) s_[sz(i * p_ + j)] -= l * s_[sz(k * p_ + j)];
    }
  }
  return true;
}

void BorderedLU::solve(double* x, double* z) const {
  solve_blocks(x, nullptr);  // x0 = A^-1 r
  if (p_ == 0) return;
  std::vector<double>& rhs = rhs_;  // s - Q x0 (kept between calls: no allocation a solve)
  rhs.assign(z, z + p_);
  for (int r = 0; r < p_; ++r)
    for (const Entry& e : qrow_[sz(r)]) rhs[sz(r)] -= e.value * x[e.index];
  for (int k = 0; k < p_; ++k) std::swap(rhs[sz(k)], rhs[sz(piv_[sz(k)])]);
  for (int i = 1; i < p_; ++i)
    for (int j = 0; j < i; ++j) rhs[sz(i)] -= s_[sz(i * p_ + j)] * rhs[sz(j)];
  for (int i = p_ - 1; i >= 0; --i) {
    for (int j = i + 1; j < p_; ++j) rhs[sz(i)] -= s_[sz(i * p_ + j)] * rhs[sz(j)];
    rhs[sz(i)] /= s_[sz(i * p_ + i)];
  }
  std::copy(rhs.begin(), rhs.end(), z);
  for (int c = 0; c < p_; ++c) {
    const double zc = z[c];
    if (zc == 0.0) continue;
    const double* col = w_.data() + sz(c) * sz(n_);
    for (int i = wlo_[sz(c)]; i < whi_[sz(c)]; ++i) x[i] -= col[i] * zc;
  }
}

}  // namespace rancf
