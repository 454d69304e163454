#include "integrator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "assembly.hpp"
#include "inertia.hpp"

namespace rancf {

namespace {
std::size_t sz(int n) { return static_cast<std::size_t>(n); }
}  // namespace

Integrator::Integrator(const Model& m, const Scheme& s)
    : m_(m),
      s_(s),
      lu_(m.n(), m.ku()),
      base_(sz(m.n())),
      fext_(sz(m.n())),
      yf_(sz(m.n())),
      fi_(sz(m.n())),
      tmp_(sz(m.n())),
      mv_(sz(m.n())),
      vf_(has_rotary_inertia(m) ? sz(m.n()) : 0),
      aam_(has_rotary_inertia(m) ? sz(m.n()) : 0) {}

StepOutcome Integrator::step(const double* y0, const double* v0, const double* a0, double t,
                             double h, double* y1, double* v1, double* a1) {
  const int n = m_.n(), ku = m_.ku();
  const double am = s_.alpha_m, af = s_.alpha_f, gamma = s_.gamma, beta = s_.beta;
  const double c = s_.damping, bh2 = beta * h * h;
  if (h != lu_h_) {  // the factors depend on h
    lu_valid_ = false;
    lu_h_ = h;
  }
  const int max_iter = s_.modified ? 3 * s_.max_iter : s_.max_iter;  // linear convergence
  for (int i = 0; i < n; ++i) {
    base_[sz(i)] = y0[i] + h * v0[i] + h * h * (0.5 - beta) * a0[i];
    y1[i] = y0[i] + h * v0[i] + 0.5 * h * h * a0[i];
  }
  const double tf = t + (1.0 - af) * h;
  const bool moments = m_.loads.n_moment > 0;  // configuration-dependent loads
  if (!moments) external_force(m_, tf, y0, fext_.data());
  const double cm = (1.0 - am) / bh2 + c * (1.0 - af) * gamma / (beta * h);
  // rods' rotary inertia (inertia.hpp): M_r(y_{1-af}) a_{1-am} + g(y_{1-af}, v_{1-af}) + c M_r v,
  // with the derivatives of the alpha points with respect to y1 as Jacobian coefficients
  const bool rotary = has_rotary_inertia(m_);
  const InertiaTerms in_terms{c, 1.0 - af, (1.0 - af) * gamma / (beta * h), (1.0 - am) / bh2};
  double prev = std::numeric_limits<double>::infinity();
  for (int it = 1; it <= max_iter; ++it) {
    for (int i = 0; i < n; ++i) {
      a1[i] = (y1[i] - base_[sz(i)]) / bh2;
      v1[i] = v0[i] + h * ((1.0 - gamma) * a0[i] + gamma * a1[i]);
      yf_[sz(i)] = (1.0 - af) * y1[i] + af * y0[i];
      tmp_[sz(i)] = (1.0 - am) * a1[i] + am * a0[i] + c * ((1.0 - af) * v1[i] + af * v0[i]);
    }
    if (rotary)
      for (int i = 0; i < n; ++i) {
        vf_[sz(i)] = (1.0 - af) * v1[i] + af * v0[i];
        aam_[sz(i)] = (1.0 - am) * a1[i] + am * a0[i];
      }
    if (moments) external_force(m_, tf, yf_.data(), fext_.data());
    const bool fresh = !s_.modified || !lu_valid_;
    if (fresh) {
      BandView jac = lu_.matrix();
      assemble(m_, yf_.data(), fi_.data(), &jac, 1.0 - af);
      if (moments) subtract_load_stiffness(m_, tf, yf_.data(), jac, 1.0 - af);
      for (int j = 0; j < n; ++j) {
        const int i0 = std::max(0, j - ku), i1 = std::min(n, j + ku + 1);
        for (int i = i0; i < i1; ++i)
          jac.at(i, j) += cm * m_.mass_band[static_cast<std::ptrdiff_t>(ku + i - j) * n + j];
      }
      if (rotary)  // ---- inertia hook 1: the rotary inertial force and its Jacobian
        assemble_inertia(m_, yf_.data(), vf_.data(), aam_.data(), in_terms, fi_.data(), &jac);
      ++factorizations_;
      lu_valid_ = lu_.factor(m_.supports.fixed);
      if (!lu_valid_) return {false, it};
    } else {
      assemble(m_, yf_.data(), fi_.data(), nullptr, 0.0);
      if (rotary)  // ---- inertia hook 1 (reused factors): the force only
        assemble_inertia(m_, yf_.data(), vf_.data(), aam_.data(), in_terms, fi_.data(), nullptr);
    }
    band_matvec(m_.mass_band, tmp_.data(), n, ku, mv_.data());
    for (int i = 0; i < n; ++i) tmp_[sz(i)] = mv_[sz(i)] + fi_[sz(i)] - fext_[sz(i)];
    lu_.solve(tmp_.data(), m_.supports.fixed);
    double norm = 0.0;
    for (int i = 0; i < n; ++i) {
      y1[i] -= tmp_[sz(i)];
      norm = std::max(norm, std::abs(tmp_[sz(i)]));
    }
    if (!std::isfinite(norm)) {
      lu_valid_ = false;
      return {false, it};
    }
    // with a fresh (exact) tangent convergence is quadratic: a small increment is a small
    // error; with reused factors the error is about |d| r / (1 - r), r = |d| / |d_prev|
    bool done = norm <= s_.tol;
    if (done && !fresh) {
      const double r = norm / prev;
      done = r < 1.0 && norm * r / (1.0 - r) <= s_.tol;
    }
    if (done) {
      for (int i = 0; i < n; ++i) {
        a1[i] = (y1[i] - base_[sz(i)]) / bh2;
        v1[i] = v0[i] + h * ((1.0 - gamma) * a0[i] + gamma * a1[i]);
      }
      return {true, it};
    }
    if (s_.modified && !fresh && norm > 0.25 * prev) lu_valid_ = false;  // slow: refresh
    prev = norm;
  }
  lu_valid_ = false;
  return {false, max_iter};
}

RunOutcome Integrator::run(double* y, double* v, double* a, double t0, double h,
                           std::int64_t n_steps, std::int64_t out_every, std::int64_t done_before,
                           double max_seconds, double* out_y, double* out_v, double* out_e) {
  const int n = m_.n();
  const auto start = std::chrono::steady_clock::now();
  std::vector<double> y1(sz(n)), v1(sz(n)), a1(sz(n));
  RunOutcome out{0, true, 0, 0};
  for (std::int64_t s = 0; s < n_steps; ++s) {
    const double t = t0 + static_cast<double>(s) * h;
    const StepOutcome st = step(y, v, a, t, h, y1.data(), v1.data(), a1.data());
    out.iterations += st.iterations;
    if (!st.converged) {
      out.converged = false;
      return out;
    }
    std::copy(y1.begin(), y1.end(), y);
    std::copy(v1.begin(), v1.end(), v);
    std::copy(a1.begin(), a1.end(), a);
    rereference_rates(m_, y, v, a);  // rods: the twist rates keep the spin (inertia.hpp)
    rereference(m_, y);
    out.steps = s + 1;
    if ((done_before + s + 1) % out_every == 0) {
      const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(out.stored) * n;
      std::copy(y, y + n, out_y + row);
      std::copy(v, v + n, out_v + row);
      out_e[3 * out.stored] = kinetic_energy(m_, y, v);
      out_e[3 * out.stored + 1] = strain_energy(m_, y);
      out_e[3 * out.stored + 2] = gravity_energy(m_, y);
      ++out.stored;
    }
    const std::chrono::duration<double> spent = std::chrono::steady_clock::now() - start;
    if (spent.count() >= max_seconds) return out;
  }
  return out;
}

void Integrator::initial_acceleration(const double* y, const double* v, double t, double* a) {
  const int n = m_.n(), ku = m_.ku();
  BandLU mass(n, ku);
  BandView mb = mass.matrix();
  for (int j = 0; j < n; ++j) {
    const int i0 = std::max(0, j - ku), i1 = std::min(n, j + ku + 1);
    for (int i = i0; i < i1; ++i)
      mb.at(i, j) = m_.mass_band[static_cast<std::ptrdiff_t>(ku + i - j) * n + j];
  }
  external_force(m_, t, y, a);
  assemble(m_, y, fi_.data(), nullptr, 0.0);
  if (has_rotary_inertia(m_))  // ---- inertia hook 2: g(y, v) + c M_r v, and M_r(y) in the matrix
    assemble_inertia(m_, y, v, nullptr, {s_.damping, 0.0, 0.0, 1.0}, fi_.data(), &mb);
  band_matvec(m_.mass_band, v, n, ku, mv_.data());
  for (int i = 0; i < n; ++i) a[i] -= fi_[sz(i)] + s_.damping * mv_[sz(i)];
  ++factorizations_;
  if (!mass.factor(m_.supports.fixed)) {
    std::fill(a, a + n, std::numeric_limits<double>::quiet_NaN());
    return;
  }
  mass.solve(a, m_.supports.fixed);
}

double kinetic_energy(const Model& m, const double* y, const double* v) {
  return kinetic_energy(m, v) + rotary_kinetic_energy(m, y, v);
}

double kinetic_energy(const Model& m, const double* v) {
  const int n = m.n();
  std::vector<double> mv(sz(n));
  band_matvec(m.mass_band, v, n, m.ku(), mv.data());
  double k = 0.0;
  for (int i = 0; i < n; ++i) k += 0.5 * v[i] * mv[sz(i)];
  return k;
}

double gravity_energy(const Model& m, const double* y) {
  double g = 0.0;
  for (int i = 0; i < m.n(); ++i) g -= m.loads.f_gravity[i] * (y[i] - m.y_ref[i]);
  return g;
}

}  // namespace rancf
