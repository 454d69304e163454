// Winches (winch.hpp; docs/derivations/variable-length.md §2).
#include "system/winch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bodies/assembly.hpp"
#include "system/system.hpp"

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

/// out += c A^T x.
void band_add_t(const std::vector<double>& ab, double c, const double* x, int n, int ku,
                double* out) {
  if (c == 0.0) return;
  for (int j = 0; j < n; ++j) {
    double total = 0.0;
    for (int i = std::max(0, j - ku); i < std::min(n, j + ku + 1); ++i)
      total += ab[sz((ku + i - j) * n + j)] * x[i];
    out[j] += c * total;
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

WinchState winch_state(const System& s, const Winch& w, double t, const double* y, const double* v,
                       const double* a) {
  if (w.drum >= 0) {
    const double length = y != nullptr ? y[w.drum] : w.length_set;
    return {length / w.length_set, length, v != nullptr ? v[w.drum] : 0.0,
            a != nullptr ? a[w.drum] : 0.0};
  }
  const TimeValue tv = evaluate(s.tfs[sz(w.length)], 0, t);
  return {tv.f / w.length_set, tv.f, tv.df, tv.ddf};
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

void drum_terms(const Model& base, const Model& scaled, const Winch& w, const WinchState& st,
                const double* y, const double* v, const double* a, double torque, double lf,
                double c, double ck, double cv, double ca, bool jacobian, DrumTerms& out) {
  // docs/derivations/variable-length.md §3.2-§3.3; rho = L / Ls the stretch of the arrays
  const int n = w.n, ku = w.ku;
  const double ls = w.length_set, rho = st.ratio, len = st.length;
  const double ld = st.rate, ldd = st.acc;
  const bool dynamic = a != nullptr;
  thread_local std::vector<double> f, fb, kb, ky, tmp;
  f.assign(sz(n), 0.0);
  fb.assign(sz(n), 0.0);
  // the strain energy's derivatives in rho (§3.3): U(y; rho) = rho U_a(y / rho) + U_b(y / rho)
  // / rho, U_a axial, U_b bending, at the arrays' length
  kb.assign(jacobian ? sz((2 * ku + 1) * n) : 0, 0.0);
  const BandView kv = numpy_band(kb.data(), n, ku);
  assemble(scaled, y, f.data(), jacobian ? &kv : nullptr, 1.0);
  const double u = strain_energy(scaled, y);
  double ub = 0.0;
  if (scaled.stiffness.ei != 0.0) {
    Model bend = scaled;
    bend.stiffness.ea = 0.0;
    bend.stiffness.axial_law = {};
    assemble(bend, y, fb.data(), nullptr, 1.0);
    ub = strain_energy(bend, y);
  }
  double fy = 0.0, fby = 0.0, qy = 0.0, xw = 0.0;
  for (int i = 0; i < n; ++i) {
    fy += f[sz(i)] * y[i];
    fby += fb[sz(i)] * y[i];
    qy += base.loads.f_gravity[i] * y[i];
  }
  for (int i = 0; i < base.dim; ++i) xw += w.weight[i] * y[w.exit + i];
  const double du = (u - fy - 2.0 * ub) / rho / ls;  // dU/dL
  const double mu = w.mass - w.rho_a * (len - ls);   // J(L) / r^2
  double r = du + lf * (xw - qy / ls + torque / w.radius);
  double yd2y = 0.0, yd2v = 0.0;
  if (dynamic) {
    yd2y = band_form(w.d2, y, y, n, ku);
    yd2v = band_form(w.d2, y, v, n, ku);
    double vmv = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = std::max(0, j - ku); i < std::min(n, j + ku + 1); ++i)
        vmv += v[i] * base.mass_band[static_cast<std::ptrdiff_t>(ku + i - j) * n + j] * v[j];
    r += mu * ldd - 0.5 * w.rho_a * ld * ld + band_form(w.c1, a, y, n, ku) +
         band_form(w.c1, v, v, n, ku) - 0.5 * vmv / ls + ldd / len * yd2y + 2.0 * ld / len * yd2v -
         0.5 * ld * ld / (len * len) * yd2y;
  }
  // a drum paid out beyond the rope it held (J(L) <= 0) has no motion: not finite, the step
  // fails
  out.residual = !dynamic || mu > 0.0 ? r : std::numeric_limits<double>::quiet_NaN();
  if (!jacobian) return;
  // d f / d rho = -(K y + 2 f_b) / rho, d2U / d rho2 = (y K y + 2 U_b + 4 f_b . y) / rho^2
  ky.assign(sz(n), 0.0);
  band_matvec(kb.data(), y, n, ku, ky.data());
  double yky = 0.0;
  for (int i = 0; i < n; ++i) yky += y[i] * ky[sz(i)];
  out.col.assign(sz(n), 0.0);
  out.row.assign(sz(n), 0.0);
  for (int i = 0; i < n; ++i) {
    const double dfl = -(ky[sz(i)] + 2.0 * fb[sz(i)]) / rho / ls;  // d f / dL
    const double dg = -lf * base.loads.f_gravity[i] / ls;          // d(-lf Q)/dL
    out.col[sz(i)] = ck * (dfl + dg);
    out.row[sz(i)] = ck * (dfl + dg);
  }
  double diag = ck * (yky + 2.0 * ub + 4.0 * fby) / (rho * rho * ls * ls) + ca * mu;
  if (dynamic) {
    // the line's rows: d/dL of rho M_s (a + c v), of the convective inertia
    tmp.resize(sz(n));
    for (int i = 0; i < n; ++i) tmp[sz(i)] = a[i] + c * v[i];
    for (int j = 0; j < n; ++j)
      for (int i = std::max(0, j - ku); i < std::min(n, j + ku + 1); ++i)
        out.col[sz(i)] +=
            ck * base.mass_band[static_cast<std::ptrdiff_t>(ku + i - j) * n + j] * tmp[sz(j)] / ls;
    const double l2 = len * len;
    band_add(w.c1, ck * 2.0 * ld * ld / l2 - cv * 4.0 * ld / len, y, n, ku, out.col.data());
    band_add(w.c2, -ck * ld * ld / l2 + cv * 2.0 * ld / len, y, n, ku, out.col.data());
    band_add(w.c1, cv * 2.0, v, n, ku, out.col.data());
    band_add(w.c1, ca, y, n, ku, out.col.data());
    // the drum's row
    band_add_t(w.c1, ck, a, n, ku, out.row.data());
    band_add(w.d2, ck * (2.0 * ldd / len - ld * ld / l2) + cv * 2.0 * ld / len, y, n, ku,
             out.row.data());
    band_add(w.d2, ck * 2.0 * ld / len, v, n, ku, out.row.data());
    band_add(w.c1, cv, v, n, ku, out.row.data());
    band_add_t(w.c1, cv, v, n, ku, out.row.data());
    band_add(w.c1, ca, y, n, ku, out.row.data());
    for (int j = 0; j < n; ++j)
      for (int i = std::max(0, j - ku); i < std::min(n, j + ku + 1); ++i)
        out.row[sz(i)] -=
            cv * base.mass_band[static_cast<std::ptrdiff_t>(ku + i - j) * n + j] * v[j] / ls;
    diag += ck * (-w.rho_a * ldd - ldd / l2 * yd2y - 2.0 * ld / l2 * yd2v +
                  ld * ld / (l2 * len) * yd2y) +
            cv * (-w.rho_a * ld + 2.0 / len * yd2v - ld / l2 * yd2y) + ca * yd2y / len;
  }
  out.diag = diag;
}

double drum_kinetic_energy(const Winch& w, const double* y, const double* v) {
  const double mu = w.mass - w.rho_a * (y[w.drum] - w.length_set);
  return 0.5 * mu * v[w.drum] * v[w.drum];
}

double drum_gravity_energy(const Winch& w, const System& s, const double* y) {
  const double* yb = y + s.offset[sz(w.body)] + w.exit;
  double xw = 0.0;
  for (int i = 0; i < s.dim; ++i) xw += w.weight[i] * yb[i];
  return (y[w.drum] - w.length_set) * xw;
}

}  // namespace rancf
