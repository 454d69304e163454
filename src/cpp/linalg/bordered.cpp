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
  p_ = pu_ = p;
  for (auto& v : pcol_) v.clear();  // (kept: their memory serves the next assembly)
  for (auto& v : qrow_) v.clear();
  if (pcol_.size() < sz(p)) {
    pcol_.resize(sz(p));
    qrow_.resize(sz(p));
  }
  du_.assign(sz(p * p), 0.0);
  far_.clear();
  merged_ = false;
}

void BorderedLU::add_p(int col, int row, double v) {
  if (v != 0.0) pcol_[sz(col)].push_back({row, v});
}
void BorderedLU::add_q(int row, int col, double v) {
  if (v != 0.0) qrow_[sz(row)].push_back({col, v});
}
void BorderedLU::add_d(int i, int j, double v) { du_[sz(i * pu_ + j)] += v; }

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
  for (const Far& e : far_) out[sz(e.i) * sz(w) + sz(e.j)] += e.v;
  for (int c = 0; c < pu_; ++c) {
    if (c < keep) {
      for (const Entry& e : pcol_[sz(c)]) out[sz(e.index) * sz(w) + sz(n_ + c)] += e.value;
      for (const Entry& e : qrow_[sz(c)]) out[sz(n_ + c) * sz(w) + sz(e.index)] += e.value;
      for (int d = 0; d < keep; ++d) out[sz(n_ + c) * sz(w) + sz(n_ + d)] += du_[sz(c * pu_ + d)];
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
  for (const Far& e : far_) put(e.i, e.j, e.v);
  for (int c = 0; c < pu_; ++c) {
    for (const Entry& e : pcol_[sz(c)]) put(e.index, n_ + c, e.value);
    for (const Entry& e : qrow_[sz(c)]) put(n_ + c, e.index, e.value);
    for (int d = 0; d < pu_; ++d) put(n_ + c, n_ + d, du_[sz(c * pu_ + d)]);
  }
}

void BorderedLU::solve_blocks(double* x, const std::vector<char>* touched) const {
  if (merged_) {
    mx_.resize(sz(n_));
    for (int k = 0; k < n_; ++k) mx_[sz(k)] = x[perm_[sz(k)]];
    big_.solve(mx_.data(), mfixed_.data());
    for (int k = 0; k < n_; ++k) x[perm_[sz(k)]] = mx_[sz(k)];
    return;
  }
  for (std::size_t b = 0; b < lu_.size(); ++b) {
    if (touched != nullptr && !(*touched)[b]) continue;  // zero there already
    lu_[b].solve(x + off_[b], fixed_[b].data());
  }
}

bool BorderedLU::factor() {
  p_ = pu_;  // the caller's border, then the unknowns of the far entries (place_far)
  for (std::size_t c = sz(pu_); c < pcol_.size(); ++c) {  // the last factor()'s far unknowns
    pcol_[c].clear();
    qrow_[c].clear();
  }
  merged_ = false;
  place_far();
  if (merged_) {
    if (!big_.factor(mfixed_.data())) return false;
  } else {
    for (std::size_t b = 0; b < lu_.size(); ++b)
      if (!lu_[b].factor(fixed_[b].data())) return false;
  }
  return factor_schur();
}

bool BorderedLU::factor_schur() {
  if (p_ == 0) return true;
  w_.resize(sz(n_) * sz(p_));
  wlo_.assign(sz(p_), n_);
  whi_.assign(sz(p_), 0);
  std::vector<char> touched(lu_.size());
  for (int c = 0; c < p_; ++c) {  // only the blocks the column touches: the rest stays zero
    double* col = w_.data() + sz(c) * sz(n_);
    std::fill(touched.begin(), touched.end(), 0);
    for (const Entry& e : pcol_[sz(c)]) touched[sz(block_of(e.index))] = 1;
    if (merged_) std::fill(touched.begin(), touched.end(), 1);  // one band: the whole column
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
  rhs.assign(z, z + pu_);
  rhs.resize(sz(p_), 0.0);  // the far entries' unknowns: zero right-hand side
  for (int r = 0; r < p_; ++r)
    for (const Entry& e : qrow_[sz(r)]) rhs[sz(r)] -= e.value * x[e.index];
  for (int k = 0; k < p_; ++k) std::swap(rhs[sz(k)], rhs[sz(piv_[sz(k)])]);
  for (int i = 1; i < p_; ++i)
    for (int j = 0; j < i; ++j) rhs[sz(i)] -= s_[sz(i * p_ + j)] * rhs[sz(j)];
  for (int i = p_ - 1; i >= 0; --i) {
    for (int j = i + 1; j < p_; ++j) rhs[sz(i)] -= s_[sz(i * p_ + j)] * rhs[sz(j)];
    rhs[sz(i)] /= s_[sz(i * p_ + i)];
  }
  std::copy(rhs.begin(), rhs.begin() + pu_, z);
  for (int c = 0; c < p_; ++c) {
    const double zc = rhs[sz(c)];
    if (zc == 0.0) continue;
    const double* col = w_.data() + sz(c) * sz(n_);
    for (int i = wlo_[sz(c)]; i < whi_[sz(c)]; ++i) x[i] -= col[i] * zc;
  }
}

void BorderedLU::place_far() {
  if (far_.empty()) {
    d_ = du_;
    return;
  }
  // each entry's group: its row's if the row holds more far entries than its column
  std::vector<int>&rows = rows_, &cols = cols_, &count = count_, &gid = gid_;
  rows.assign(sz(n_), 0);
  cols.assign(sz(n_), 0);
  count.assign(sz(2 * n_ + 1), 0);
  gid.resize(far_.size());
  for (const Far& e : far_) {
    ++rows[sz(e.i)];
    ++cols[sz(e.j)];
  }
  for (std::size_t k = 0; k < far_.size(); ++k) {
    const Far& e = far_[k];
    gid[k] = rows[sz(e.i)] > cols[sz(e.j)] ? n_ + e.i : e.j;
    ++count[sz(gid[k])];
  }
  int kmax = 0;
  for (const BandLU& b : lu_) kmax = std::max(kmax, b.ku());
  // the cheapest of: (a) every group an unknown; (b) every entry in the merged band; (c) the
  // groups longer than two band rows (a rigid body's coupling with a line) unknowns, the rest
  // merged; by operation counts: a band LU 4 n k^2, an unknown's column solve with its row
  // and column of the Schur complement 20 n k (measured: twice the flops of the solve, which
  // runs slower than the factorization's loops), the Schur LU 2 g^3 / 3
  const int dense = 2 * (2 * kmax + 1);
  auto short_entries = [&]() {
    std::vector<Far> out;
    for (std::size_t k = 0; k < far_.size(); ++k)
      if (count[sz(gid[k])] <= dense) out.push_back(far_[k]);
    return out;
  };
  // the choice and the order are kept while the far entries' pattern stays (a hash of their
  // positions in the order they came: a step's contacts; and, against a collision, the
  // merged entries within the kept band); a merged band is kept for another pattern too
  // while that pattern's merged entries fit in it (contacts that come and go between Newton
  // iterations and steps)
  std::uint64_t sig = 1469598103934665603ull ^ far_.size();
  for (const Far& e : far_)
    sig = (sig ^ (static_cast<std::uint64_t>(e.i) << 32 ^ static_cast<std::uint64_t>(e.j))) *
          1099511628211ull;
  auto fits = [&]() {  // the kept order holds the merged entries within its band
    if (choice_ == 0) return true;
    for (std::size_t k = 0; k < far_.size(); ++k)
      if ((choice_ == 1 || count[sz(gid[k])] <= dense) &&
          std::abs(pos_[sz(far_[k].i)] - pos_[sz(far_[k].j)]) > kb_)
        return false;
    return true;
  };
  const bool kept = perm_.size() == sz(n_) && (sig == sig_ || choice_ > 0) && fits();
  if (!kept) {
    sig_ = sig;
    int groups = 0, long_groups = 0;
    for (int c : count) {
      groups += c > 0 ? 1 : 0;
      long_groups += c > dense ? 1 : 0;
    }
    const std::vector<Far> rest = short_entries();
    const bool split = long_groups > 0 && !rest.empty();
    const double n = n_;
    auto cost = [n](double k, double g) {
      return 4.0 * n * k * k + 20.0 * g * n * k + g * g * g / 1.5;
    };
    const double cost_a = cost(kmax, groups);
    const int kb_b = order(far_);
    const double cost_b = cost(kb_b, 0.0);
    const int kb_c = split ? order(rest) : 0;  // the last order() computed: (c)'s if split
    const double cost_c = split ? cost(kb_c, long_groups) : cost_b + 1.0;
    choice_ = std::min(cost_b, cost_c) >= cost_a ? 0 : (cost_c < cost_b ? 2 : 1);
    kb_ = choice_ == 2 ? kb_c : kb_b;
    if (choice_ == 1 && split) order(far_);
  }
  merged_ = choice_ > 0;
  const int limit = choice_ == 0 ? -1 : (choice_ == 2 ? dense : static_cast<int>(far_.size()));
  // the entries that become unknowns, grouped (columns, then rows, each ascending) by a
  // counting sort; their order within a group kept
  std::vector<int>&at = at_, &idx = idx_;
  at.assign(sz(2 * n_ + 1), 0);
  int total = 0;
  for (int gk = 0; gk < 2 * n_; ++gk) {
    at[sz(gk)] = total;
    if (count[sz(gk)] > limit) total += count[sz(gk)];
  }
  idx.resize(sz(total));
  for (int k = 0; k < static_cast<int>(far_.size()); ++k) {
    const int gk = gid[sz(k)];
    if (count[sz(gk)] > limit) idx[sz(at[sz(gk)]++)] = k;
  }
  int z = pu_ - 1, last = -1;
  std::vector<int>& key = keys_;
  key.clear();
  for (int k : idx) {
    const Far& e = far_[sz(k)];
    const int gk = gid[sz(k)];
    if (gk != last) {
      ++z;
      last = gk;
      key.push_back(gk);
      if (pcol_.size() <= sz(z)) {
        pcol_.emplace_back();
        qrow_.emplace_back();
      }
    }
    if (gk >= n_)  // w = K_i. x: Q[w][j] = K_ij, P[i][w] = 1
      qrow_[sz(z)].push_back({e.j, e.v});
    else  // z = x_j: P[i][z] = K_ij, Q[z][j] = 1
      pcol_[sz(z)].push_back({e.i, e.v});
  }
  p_ = pu_ + static_cast<int>(key.size());
  d_.assign(sz(p_ * p_), 0.0);
  for (int i = 0; i < pu_; ++i)
    for (int j = 0; j < pu_; ++j) d_[sz(i * p_ + j)] = du_[sz(i * pu_ + j)];
  for (int c = pu_; c < p_; ++c) {
    const int gk = key[sz(c - pu_)];
    if (gk >= n_)
      pcol_[sz(c)].push_back({gk - n_, 1.0});
    else
      qrow_[sz(c)].push_back({gk, 1.0});
    d_[sz(c * p_ + c)] = -1.0;
  }
  if (choice_ == 1) fill_merged(far_, kb_);
  if (choice_ == 2) fill_merged(short_entries(), kb_);
}

int BorderedLU::order(const std::vector<Far>& rest) {
  // A's pattern without the held coordinates (identity rows and columns): the blocks' bands
  // and the far entries, symmetric
  std::vector<std::uint8_t> held(sz(n_));
  for (std::size_t b = 0; b < lu_.size(); ++b)
    std::copy(fixed_[b].begin(), fixed_[b].end(), held.begin() + off_[b]);
  std::vector<std::vector<int>> adj(sz(n_));
  auto link = [&](int i, int j) {
    if (i == j || held[sz(i)] || held[sz(j)]) return;
    adj[sz(i)].push_back(j);
    adj[sz(j)].push_back(i);
  };
  for (std::size_t b = 0; b < lu_.size(); ++b)
    for (int i = 0; i < size_[b]; ++i)
      for (int j = i + 1; j <= std::min(size_[b] - 1, i + lu_[b].ku()); ++j)
        link(off_[b] + i, off_[b] + j);
  for (const Far& e : rest) link(e.i, e.j);
  for (auto& a : adj) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
  }
  auto degree = [&](int i) { return adj[sz(i)].size(); };
  for (auto& a : adj)
    std::stable_sort(a.begin(), a.end(), [&](int x, int y) { return degree(x) < degree(y); });
  // Cuthill-McKee by components, each from a pseudo-peripheral node (the last level of a
  // breadth-first search from its node of least degree, once), then reversed
  std::vector<int> seen(sz(n_), 0), cm;
  cm.reserve(sz(n_));
  auto bfs = [&](int start, int mark, std::vector<int>& out) {
    out.clear();
    out.push_back(start);
    seen[sz(start)] = mark;
    for (std::size_t h = 0; h < out.size(); ++h)
      for (int j : adj[sz(out[h])])
        if (seen[sz(j)] != mark) {
          seen[sz(j)] = mark;
          out.push_back(j);
        }
  };
  std::vector<int> comp, probe;
  for (int s0 = 0; s0 < n_; ++s0) {
    if (seen[sz(s0)] != 0) continue;
    bfs(s0, -1, comp);  // the component: its node of least degree
    int start = s0;
    for (int i : comp)
      if (degree(i) < degree(start)) start = i;
    bfs(start, -2, probe);
    start = probe.back();
    for (int i : probe) seen[sz(i)] = -1;  // the probe's marks back to the component's
    bfs(start, 1, probe);
    cm.insert(cm.end(), probe.begin(), probe.end());
  }
  perm_.assign(cm.rbegin(), cm.rend());
  pos_.assign(sz(n_), 0);
  for (int k = 0; k < n_; ++k) pos_[sz(perm_[sz(k)])] = k;
  int kb = 0;
  for (int i = 0; i < n_; ++i)
    for (int j : adj[sz(i)]) kb = std::max(kb, std::abs(pos_[sz(i)] - pos_[sz(j)]));
  return kb;
}

void BorderedLU::fill_merged(const std::vector<Far>& rest, int kb) {
  if (big_.n() != n_ || big_.ku() != kb) big_ = BandLU(n_, kb);
  const BandView a = big_.matrix();
  mfixed_.assign(sz(n_), 0);
  for (std::size_t b = 0; b < lu_.size(); ++b) {
    const BandView v = lu_[b].view();
    const int o = off_[b], nb = size_[b], ku = lu_[b].ku();
    for (int i = 0; i < nb; ++i) {
      const int pi = pos_[sz(o + i)];
      mfixed_[sz(pi)] = fixed_[b][sz(i)];
      if (fixed_[b][sz(i)]) continue;
      for (int j = std::max(0, i - ku); j < std::min(nb, i + ku + 1); ++j)
        if (!fixed_[b][sz(j)]) a.at(pi, pos_[sz(o + j)]) += v.at(i, j);
    }
  }
  for (const Far& e : rest) {
    const int pi = pos_[sz(e.i)], pj = pos_[sz(e.j)];
    if (!mfixed_[sz(pi)] && !mfixed_[sz(pj)]) a.at(pi, pj) += e.v;
  }
}

}  // namespace rancf
