// Winches (winch.hpp; docs/derivations/variable-length.md §2).
#include "winch.hpp"

#include <algorithm>
#include <cmath>

#include "system.hpp"

namespace rancf {

namespace {

std::size_t sz(int i) { return static_cast<std::size_t>(i); }

/// out = A x + out for a (2 ku + 1, n) C-order band matrix scaled by c.
void band_add(const std::vector<double>& ab, double c, const double* x, int n, int ku,
              double* out) {
  if (c == 0.0) return;
  for (int j = 0; j < n; ++j) {
    const double xj = c * x[j];
    if (xj == 0.0) continue;
    for (int i = std::max(0, j - ku); i < std::min(n, j + ku + 1); ++i)
      out[i] += ab[sz((ku + i - j) * n + j)] * xj;
  }
}

double band_form(const std::vector<double>& ab, const double* x, const double* y, int n, int ku) {
  double total = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = std::max(0, j - ku); i < std::min(n, j + ku + 1); ++i)
      total += x[i] * ab[sz((ku + i - j) * n + j)] * y[j];
  return total;
}

}  // namespace

const Winch* winch_of(const System& s, std::size_t b) {
  if (s.winches == nullptr || b >= s.winches->of_body.size()) return nullptr;
  const int w = s.winches->of_body[b];
  return w < 0 ? nullptr : &s.winches->winches[sz(w)];
}

WinchState winch_state(const System& s, const Winch& w, double t) {
  const TimeValue v = evaluate(s.tfs[sz(w.length)], 0, t);
  return {v.f / w.length_set, v.f, v.df, v.ddf};
}

const Model& scaled_model(const Model& m, double ratio, ScaledBody& out) {
  out.model = m;
  if (ratio == 1.0) return out.model;
  const std::size_t nq = sz(m.n_el * m.cable.n_qp), n = sz(m.n());
  const CableData& c = m.cable;
  out.s0.resize(nq);
  out.j0.resize(nq);
  out.k0.resize(nq);
  out.qr.resize(nq);
  for (std::size_t k = 0; k < nq; ++k) {
    out.s0[k] = ratio * ratio * c.s0[k];
    out.j0[k] = ratio * c.j0[k];
    out.k0[k] = c.k0[k] / ratio;
    out.qr[k] = c.qr[k] / (ratio * ratio);
  }
  const std::size_t nb = sz(2 * m.ku() + 1) * n;
  out.mass.assign(m.mass_band, m.mass_band + nb);
  for (double& x : out.mass) x *= ratio;
  out.gravity.assign(m.loads.f_gravity, m.loads.f_gravity + n);
  for (double& x : out.gravity) x *= ratio;
  out.model.cable.s0 = out.s0.data();
  out.model.cable.j0 = out.j0.data();
  out.model.cable.k0 = out.k0.data();
  out.model.cable.qr = out.qr.data();
  out.model.mass_band = out.mass.data();
  out.model.loads.f_gravity = out.gravity.data();
  return out.model;
}

void winch_inertia(const Winch& w, const WinchState& st, const double* y, const double* v,
                   double ck, double cv, double* r, const BandView* jac) {
  const double cy1 = st.acc - 2.0 * st.rate * st.rate / st.length;
  const double cy2 = st.rate * st.rate / st.length;
  const double cv1 = 2.0 * st.rate;
  band_add(w.c1, cv1, v, w.n, w.ku, r);
  band_add(w.c1, cy1, y, w.n, w.ku, r);
  band_add(w.c2, cy2, y, w.n, w.ku, r);
  if (jac == nullptr) return;
  const int n = w.n, ku = w.ku;
  for (int j = 0; j < n; ++j)
    for (int i = std::max(0, j - ku); i < std::min(n, j + ku + 1); ++i) {
      const std::size_t at = sz((ku + i - j) * n + j);
      jac->at(i, j) += cv * cv1 * w.c1[at] + ck * (cy1 * w.c1[at] + cy2 * w.c2[at]);
    }
}

double winch_kinetic_energy(const Model& m, const Winch& w, const WinchState& st, const double* y,
                            const double* v) {
  const int n = w.n, ku = w.ku;
  double mass = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = std::max(0, j - ku); i < std::min(n, j + ku + 1); ++i)
      mass += v[i] * m.mass_band[static_cast<std::ptrdiff_t>(ku + i - j) * n + j] * v[j];
  return 0.5 * mass + st.rate * band_form(w.c1, v, y, n, ku) +
         0.5 * st.rate * st.rate / st.length * band_form(w.d2, y, y, n, ku);
}

double winch_gravity_energy(const Model& m, const WinchState& st0, const WinchState& st,
                            const double* y) {
  double now = 0.0, start = 0.0;
  for (int i = 0; i < m.n(); ++i) {
    now += m.loads.f_gravity[i] * y[i];
    start += m.loads.f_gravity[i] * (m.y_ref != nullptr ? m.y_ref[i] : 0.0);
  }
  return -st.ratio * now + st0.ratio * start;
}

}  // namespace rancf
