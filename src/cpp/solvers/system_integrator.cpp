#include "solvers/system_integrator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "bodies/assembly.hpp"
#include "bodies/inertia.hpp"
#include "bodies/sections.hpp"
#include "contact/contact.hpp"
#include "elements/registry.hpp"
#include "fluid/fluid.hpp"
#include "system/sliding.hpp"
#include "system/spring_law.hpp"
#include "system/winch.hpp"

namespace rancf {

namespace {
std::size_t sz(int i) { return static_cast<std::size_t>(i); }
}  // namespace

SystemIntegrator::SystemIntegrator(const System& s, const Scheme& scheme)
    : s_(s),
      sc_(scheme),
      lu_(s.offset, s.block_size, s.block_ku, s.fixed.data()),
      base_(sz(s.n)),
      yf_(sz(s.n)),
      vf_(sz(s.n)),
      am_(sz(s.n)),
      r_(sz(s.n + s.m)),
      dz_(sz(s.n + s.m)) {
  // no constraints, rigid bodies, rotary inertia or contact: [M G^T; G 0] is M, whatever the
  // state (the element tangents count zero times in it)
  mass_constant_ = s.m == 0 && s.rigid.empty() && s.contact == nullptr;
  contact_ = s.contact != nullptr;
  // contact switches within a step, where reused factors lead the iteration astray (rejected
  // steps): chord is full Newton there
  if (s.contact != nullptr) sc_.chord = false;
  for (const Model* mod : s.flex) mass_constant_ = mass_constant_ && !has_rotary_inertia(*mod);
  if (s.winches != nullptr && s.winches->drums > 0) mass_constant_ = false;  // J(L), C1 y
  if (s.fluid != nullptr)  // added mass along the line's tangent, and only where it is wet
    for (const LineFluid& ln : s.fluid->lines)
      if (ln.hydro && (ln.can != 0.0 || ln.cat != 0.0)) mass_constant_ = false;
}

void SystemIntegrator::solve_negative() {
  // dz = -[A P; Q D]^-1 r: the border holds the multipliers (m) and the couplings' unknowns,
  // whose right-hand side is zero
  const int n = s_.n, m = s_.m, p = lu_.border();
  zb_.assign(sz(p), 0.0);
  for (int i = 0; i < n; ++i) dz_[sz(i)] = -r_[sz(i)];
  for (int i = 0; i < m; ++i) zb_[sz(i)] = -r_[sz(n + i)];
  lu_.solve(dz_.data(), zb_.data());
  for (int i = 0; i < m; ++i) dz_[sz(n + i)] = zb_[sz(i)];
}

void SystemIntegrator::set_prescribed(double t, double* y, double* v, double* a) const {
  for (const Prescribed& p : s_.prescribed) {
    const TimeValue u = evaluate(s_.tfs[sz(p.tf)], p.comp, t);
    if (y != nullptr) y[p.coord] = p.base + u.f;
    if (v != nullptr) v[p.coord] = u.df;
    if (a != nullptr) a[p.coord] = u.ddf;
  }
}

void SystemIntegrator::set_increment_scale(std::vector<double> scale) {
  scale_ = std::move(scale);
  error_scale_ = scale_.empty() ? std::vector<double>(sz(s_.n), 1.0) : scale_;
  for (const Prescribed& p : s_.prescribed) error_scale_[sz(p.coord)] = 0.0;  // exact there
}

StepOutcome SystemIntegrator::step(const StepIn& s0, double t, double h, const StepOut& s1) {
  StepOutcome out;
  if (contact_ && !start_residual(s0, t)) return out;
  if (from_y0_ > 0 && from_y0_ < kFromY0Steps) {  // the steps before started again from y0
    out = iterate(s0, t, h, s1, true);
    if (out.converged) {
      ++from_y0_;
    } else {
      from_y0_ = 0;
      const StepOutcome again = iterate(s0, t, h, s1, false);
      out.converged = again.converged;
      out.iterations += again.iterations;
    }
  } else {
    const StepOutcome first = iterate(s0, t, h, s1, false);
    out = first;
    if (!first.converged) {
      // once more from y0: the predictor carries the stiff modes' alternating accelerations
      // into the positions (docs/derivations/newton.md), where Newton may not converge
      out = iterate(s0, t, h, s1, true);
      out.iterations += first.iterations;
    }
    from_y0_ = !out.converged || first.converged ? 0 : 1;
  }
  if (out.converged) {
    project_rates(s1, t + h);
    out.error = local_error(s0.w, s1.w, h);
    if (!strain_points_.empty()) {  // the error vector (TI.8) in the bodies' strains (TI.13)
      const double c = std::abs(sc_.beta - 0.5 * sc_.gamma + 1.0 / 12.0) * h * h;
      std::vector<double>& e = am_;
      for (int i = 0; i < s_.n; ++i)
        e[sz(i)] = error_scale_[sz(i)] > 0.0 ? c * (s1.w[i] - s0.w[i]) : 0.0;
      out.error = std::max(out.error, strain_error(s1.y, e.data()));
    }
    if (error_tol_ > 0.0 && out.error > error_tol_ && lu_valid_)
      out.error = std::min(out.error, filtered_error(s0, s1, t + h, h));
  }
  return out;
}

AssemblyTerms SystemIntegrator::step_terms(double t, double h) const {
  const double af = sc_.alpha_f, bh2 = sc_.beta * h * h;
  AssemblyTerms terms;
  terms.ck = 1.0;
  terms.cv = sc_.gamma / (sc_.beta * h);
  terms.ca = (1.0 - sc_.alpha_m) / ((1.0 - af) * bh2);
  terms.tf = t + h;
  terms.t1 = t + h;
  if (contact_) {  // s P(yf, vf, y1), s = 1/(1 - af): d/dy1 = ck d/dyf + cv d/dvf + s d/dy1
    terms.contact_step = true;
    terms.contact_scale = 1.0 / (1.0 - af);
    terms.c1 = 1.0 / (1.0 - af);
    terms.contact_yf = yf_.data();
    terms.contact_vf = vf_.data();
  }
  return terms;
}

bool SystemIntegrator::start_residual(const StepIn& s0, double t) {
  AssemblyTerms terms;  // R_n: the balance's residual at the step's start without contact
  terms.tf = t;
  terms.t1 = t;
  terms.skip_contact = true;
  r0_.resize(r_.size());
  return assemble_system(s_, s0.y, s0.v, s0.a, s0.lam, s0.y, terms, r0_.data(), nullptr);
}

double SystemIntegrator::filtered_error(const StepIn& s0, const StepOut& s1, double t1, double h) {
  const int n = s_.n;
  const double c = std::abs(sc_.beta - 0.5 * sc_.gamma + 1.0 / 12.0) * h * h;
  const double bh2 = sc_.beta * h * h;
  const double ca = (1.0 - sc_.alpha_m) / ((1.0 - sc_.alpha_f) * bh2);
  std::vector<double>& e = yf_;
  std::vector<double>& r0 = vf_;
  for (int i = 0; i < n; ++i) e[sz(i)] = error_scale_[sz(i)] > 0.0 ? c * (s1.w[i] - s0.w[i]) : 0.0;
  AssemblyTerms terms;  // the residual only: M e = r(a = e) - r(a = 0) at the step's end
  terms.tf = t1;
  terms.t1 = t1;
  std::fill(am_.begin(), am_.end(), 0.0);
  if (!assemble_system(s_, s1.y, s1.v, am_.data(), s1.lam, s1.y, terms, r_.data(), nullptr))
    return std::numeric_limits<double>::infinity();
  std::copy(r_.begin(), r_.begin() + n, r0.begin());
  if (!assemble_system(s_, s1.y, s1.v, e.data(), s1.lam, s1.y, terms, r_.data(), nullptr))
    return std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) r_[sz(i)] = ca * (r_[sz(i)] - r0[sz(i)]);
  std::fill(r_.begin() + n, r_.end(), 0.0);
  solve_negative();  // dz = -S^-1 c_a M e
  double out = 0.0;
  for (int i = 0; i < n; ++i) out = std::max(out, std::abs(dz_[sz(i)]) * error_scale_[sz(i)]);
  if (strain_points_.empty()) return out;
  // the strains: filtered once more (TI.13), so that what the step does not resolve counts
  // by its amplitude over (omega h)^2, and the resolved motion as before
  for (int i = 0; i < n; ++i) e[sz(i)] = dz_[sz(i)];
  if (!assemble_system(s_, s1.y, s1.v, e.data(), s1.lam, s1.y, terms, r_.data(), nullptr))
    return std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) r_[sz(i)] = ca * (r_[sz(i)] - r0[sz(i)]);
  std::fill(r_.begin() + n, r_.end(), 0.0);
  solve_negative();
  return std::max(out, strain_error(s1.y, dz_.data()));
}

bool SystemIntegrator::add_strain_points(int b, std::vector<double> xi, std::vector<double> n1,
                                         std::vector<double> n2, std::vector<double> ref,
                                         double floor, double length) {
  if (b < 0 || sz(b) >= s_.flex.size()) return false;
  const Model& mod = *s_.flex[sz(b)];
  const std::size_t points = sz(mod.n_el) * xi.size();
  if (!kernel_for(mod).centre_line || n1.size() != 4 * points || n2.size() != n1.size() ||
      ref.size() != points || !(floor > 0.0))
    return false;
  StrainPoints p;
  p.body = b;
  p.xi = std::move(xi);
  p.n1 = std::move(n1);
  p.n2 = std::move(n2);
  p.ref = std::move(ref);
  p.floor = floor;
  p.length = length;
  strain_points_.push_back(std::move(p));
  return true;
}

double SystemIntegrator::strain_error(const double* y1, const double* e) {
  double out = 0.0;
  for (const StrainPoints& p : strain_points_) {
    const Model& mod = *s_.flex[sz(p.body)];
    const int o = s_.offset[sz(p.body)], nb = mod.n(), w = section_width(mod);
    const int np = static_cast<int>(p.xi.size());
    const SamplePoints pts{np, p.xi.data(), p.n1.data(), p.n2.data(), p.ref.data()};
    const auto k = sz(mod.n_el * np * w);
    strain_a_.resize(k);
    strain_b_.resize(k);
    strain_y_.assign(y1 + o, y1 + o + nb);
    section_strains(mod, pts, strain_y_.data(), strain_a_.data());
    for (int i = 0; i < nb; ++i) strain_y_[sz(i)] += e[o + i];
    section_strains(mod, pts, strain_y_.data(), strain_b_.data());
    double de = 0.0, eps = p.floor;
    for (std::size_t i = 0; i < k; i += sz(w)) {
      de = std::max(de, std::abs(strain_b_[i] - strain_a_[i]));
      eps = std::max(eps, std::abs(strain_a_[i]));
    }
    out = std::max(out, p.length * de / eps);
  }
  return out;
}

void SystemIntegrator::project_rates(const StepOut& s1, double t1) {
  // v1 -= S^-1 G^T (G S^-1 G^T)^-1 c, c = G v1 + g_t = d/ds g(y1 + s v1, t1 + s) at s = 0
  // (TI.11 of docs/derivations/time-integration.md), with the factors of the step's
  // iteration matrix [S G^T; G 0]
  const int n = s_.n, m = s_.m;
  // sliding joints: their material coordinates' rows are not rates of positions (their
  // reeving ran its rope out with the projection), so such systems keep index 3
  if (m == 0 || !lu_valid_ || !s_.slots.empty()) return;
  double scale = 1.0;
  for (int i = 0; i < n; ++i) scale = std::max(scale, std::abs(s1.v[i]));
  const double e = 1e-5 / scale;  // central: truncation ~e^2 and rounding ~1e-16/e balanced
  std::vector<double>& y = yf_;
  std::vector<double>& gm = rate_g_;
  gm.resize(sz(m));
  for (int i = 0; i < n; ++i) y[sz(i)] = s1.y[i] + e * s1.v[i];
  constraints(s_, y.data(), t1 + e, r_.data() + n, s1.lam);
  for (int i = 0; i < n; ++i) y[sz(i)] = s1.y[i] - e * s1.v[i];
  constraints(s_, y.data(), t1 - e, gm.data(), s1.lam);
  std::fill(r_.begin(), r_.begin() + n, 0.0);
  for (int i = 0; i < m; ++i) r_[sz(n + i)] = (r_[sz(n + i)] - gm[sz(i)]) / (2.0 * e);
  solve_negative();
  for (int i = 0; i < n; ++i) s1.v[i] += dz_[sz(i)];
}

double SystemIntegrator::local_error(const double* w0, const double* w1, double h) const {
  if (error_scale_.size() != sz(s_.n)) return 0.0;  // set_increment_scale not called
  double e = 0.0;
  for (int i = 0; i < s_.n; ++i) e = std::max(e, std::abs(w1[i] - w0[i]) * error_scale_[sz(i)]);
  return std::abs(sc_.beta - 0.5 * sc_.gamma + 1.0 / 12.0) * h * h * e;
}

double SystemIntegrator::damp_reversal(double factor, const double* w) {
  // a full Newton increment that turns back along the step before (cosine below -1/2, scaled
  // as the convergence test) without being shorter than half of it: the iterates circle a
  // root where the forces saturate (regularized friction); the factor on the increment is
  // halved at each such turn and doubled (up to 1) at each other iteration
  const int n = s_.n;
  double dot = 0.0, a2 = 0.0, b2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double sc = w != nullptr ? w[i] * w[i] : 1.0;
    dot += sc * dz_[sz(i)] * prev_dz_[sz(i)];
    a2 += sc * dz_[sz(i)] * dz_[sz(i)];
    b2 += sc * prev_dz_[sz(i)] * prev_dz_[sz(i)];
  }
  const bool turn = dot < -0.5 * std::sqrt(a2 * b2) && a2 > 0.25 * b2;
  factor = turn ? 0.5 * factor : std::min(1.0, 2.0 * factor);
  if (factor < 1.0)
    for (double& d : dz_) d *= factor;
  return factor;
}

StepOutcome SystemIntegrator::iterate(const StepIn& s0, double t, double h, const StepOut& s1,
                                      bool from_y0) {
  const int n = s_.n, m = s_.m;
  const double am = sc_.alpha_m, af = sc_.alpha_f, gamma = sc_.gamma, beta = sc_.beta;
  const double bh2 = beta * h * h;
  const double *y0 = s0.y, *v0 = s0.v, *a0 = s0.a, *w0 = s0.w;
  double *y1 = s1.y, *v1 = s1.v, *a1 = s1.a, *w1 = s1.w, *l1 = s1.lam;
  if (h != lu_h_ || sc_.chord) {  // the factors depend on h; chord: fresh at each step
    lu_valid_ = false;
    lu_h_ = h;
  }
  bool reuse = sc_.modified || sc_.chord;
  // modified: linear convergence (old factors); chord: a fresh tangent at each step's start;
  // a slow contraction ends the attempt from the predictor (step() starts again from y0), and
  // from y0 it goes on with full Newton
  const int max_iter = sc_.modified ? 3 * sc_.max_iter : sc_.max_iter;
  for (int i = 0; i < n; ++i) {
    base_[sz(i)] = y0[i] + h * v0[i] + h * h * (0.5 - beta) * w0[i];
    y1[i] = from_y0 ? y0[i] : y0[i] + h * v0[i] + 0.5 * h * h * w0[i];
  }
  set_prescribed(t + h, y1, nullptr, nullptr);
  std::copy(s0.lam, s0.lam + m, l1);
  // the balance at t + h (TI.1-TI.6): d a1/d y1 = (1 - am)/((1 - af) beta h^2)
  const bool ch = contact_;
  AssemblyTerms terms = step_terms(t, h);
  double prev = std::numeric_limits<double>::infinity(), factor = 1.0;
  const double* w = scale_.empty() ? nullptr : scale_.data();
  auto rates = [&]() {  // w1, v1 and a1 of y1 (the Newmark relations and the alpha blend)
    for (int i = 0; i < n; ++i) {
      w1[i] = (y1[i] - base_[sz(i)]) / bh2;
      v1[i] = v0[i] + h * ((1.0 - gamma) * w0[i] + gamma * w1[i]);
      a1[i] = ((1.0 - am) * w1[i] + am * w0[i] - af * a0[i]) / (1.0 - af);
      if (!ch) continue;  // contact: its forces at the alpha point (sec. 4)
      yf_[sz(i)] = (1.0 - af) * y1[i] + af * y0[i];
      vf_[sz(i)] = (1.0 - af) * v1[i] + af * v0[i];
    }
  };
  const double* yb = y1;  // the balance's state
  const double* vb = v1;
  const double* ab = a1;
  const double carry = af / (1.0 - af);  // contact: the start's residual R_n (sec. 4)
  for (int it = 1; it <= max_iter; ++it) {
    rates();
    const bool fresh = !reuse || !lu_valid_;
    if (fresh) mass_factored_ = false;  // the assembly below writes into lu_
    if (!assemble_system(s_, yb, vb, ab, l1, y1, terms, r_.data(), fresh ? &lu_ : nullptr)) {
      lu_valid_ = false;
      return {false, it};
    }
    if (ch)
      for (int i = 0; i < n; ++i) r_[sz(i)] += carry * r0_[sz(i)];
    if (fresh) {
      ++factorizations_;
      lu_valid_ = lu_.factor();
      if (!lu_valid_) return {false, it};
      if (sc_.modified) remember(h, terms, yb, vb, ab, l1, y1);
    }
    solve_negative();
    if (fresh && it > 3) factor = damp_reversal(factor, w);  // after Newton's quadratic start
    prev_dz_.assign(dz_.begin(), dz_.end());                 // the step taken
    double norm = 0.0;  // increments measured as displacements (docs/derivations/newton.md)
    for (int i = 0; i < n; ++i) {
      y1[i] += dz_[sz(i)];
      norm = std::max(norm, std::abs(dz_[sz(i)]) * (w != nullptr ? w[i] : 1.0));
    }
    for (int i = 0; i < m; ++i) l1[i] += dz_[sz(n + i)];
    if (!std::isfinite(norm)) {
      lu_valid_ = false;
      return {false, it};
    }
    // with a fresh (exact) tangent convergence is quadratic: a small increment is a small
    // error; with reused factors the error is about |d| r / (1 - r), r = |d| / |d_prev|
    bool done = norm <= sc_.tol && factor == 1.0;  // a damped increment: once more
    if (done && !fresh) {
      const double r = norm / prev;
      done = r < 1.0 && norm * r / (1.0 - r) <= sc_.tol;
    }
    if (done) {
      rates();
      return {true, it};
    }
    if (reuse && !fresh && norm > 0.25 * prev) {  // slow: refresh
      lu_valid_ = false;
      if (sc_.chord && !from_y0) return {false, it};  // step() starts again from y0
      if (sc_.chord) {  // undo the chord increment, full Newton for the rest of the step: the
        for (int i = 0; i < n; ++i) y1[i] -= dz_[sz(i)];  // path of full Newton (contact)
        for (int i = 0; i < m; ++i) l1[i] -= dz_[sz(n + i)];
        reuse = false;
        continue;
      }
    }
    prev = norm;
  }
  lu_valid_ = false;
  return {false, max_iter};
}

void SystemIntegrator::remember(double h, const AssemblyTerms& terms, const double* yf,
                                const double* vf, const double* am, const double* l1,
                                const double* y1) {
  const int n = s_.n, m = s_.m;
  factored_at_.assign({h, terms.ck, terms.cv, terms.ca, terms.tf, terms.t1});
  for (const double* x : {yf, vf, am, y1}) factored_at_.insert(factored_at_.end(), x, x + n);
  factored_at_.insert(factored_at_.end(), l1, l1 + m);
  if (contact_)  // the contact's alpha point
    for (const double* x : {yf_.data(), vf_.data()})
      factored_at_.insert(factored_at_.end(), x, x + n);
}

std::vector<double> SystemIntegrator::memory() const {
  std::vector<double> out{static_cast<double>(from_y0_)};
  if (sc_.modified && lu_valid_) out.insert(out.end(), factored_at_.begin(), factored_at_.end());
  return out;
}

bool SystemIntegrator::restore(const std::vector<double>& saved, long factorizations) {
  const auto n = sz(s_.n), m = sz(s_.m), point = 6 + (contact_ ? 6 : 4) * n + m;
  factorizations_ = factorizations;
  lu_valid_ = false;
  factored_at_.clear();
  from_y0_ = 0;
  std::vector<double> memory(saved);
  if (memory.size() == 1 || memory.size() == point + 1) {  // [s] first (else rancf 0.2)
    const double s = memory[0];
    if (!(s >= 0.0 && s <= kFromY0Steps && s == std::floor(s))) return false;
    from_y0_ = static_cast<int>(s);
    memory.erase(memory.begin());
  }
  if (memory.empty()) return true;
  if (!sc_.modified || memory.size() != point) return false;
  const double* p = memory.data() + 6;
  AssemblyTerms terms = step_terms(memory[5] - memory[0], memory[0]);
  if (contact_) {
    std::copy(p + 4 * n + m, p + 5 * n + m, yf_.begin());
    std::copy(p + 5 * n + m, p + 6 * n + m, vf_.begin());
  }
  terms.ck = memory[1];
  terms.cv = memory[2];
  terms.ca = memory[3];
  terms.tf = memory[4];
  terms.t1 = memory[5];
  if (!assemble_system(s_, p, p + n, p + 2 * n, p + 4 * n, p + 3 * n, terms, r_.data(), &lu_))
    return false;
  lu_valid_ = lu_.factor();
  if (lu_valid_) {
    lu_h_ = memory[0];
    factored_at_ = memory;
  }
  return lu_valid_;
}

RunOutcome SystemIntegrator::run(const StepOut& x, double t0, double h, std::int64_t n_steps,
                                 std::int64_t out_every, std::int64_t done_before,
                                 double max_seconds, double* out_y, double* out_v, double* out_l,
                                 double* out_e, double* out_yf, double* out_vf, double out_dt,
                                 std::int64_t k_last) {
  const int n = s_.n, m = s_.m;
  const auto start = std::chrono::steady_clock::now();
  std::vector<double> y1(sz(n)), v1(sz(n)), a1(sz(n)), w1(sz(n)), l1(sz(m));
  const StepIn s0{x.y, x.v, x.a, x.w, x.lam};
  const StepOut s1{y1.data(), v1.data(), a1.data(), w1.data(), l1.data()};
  RunOutcome out;
  std::int64_t since = done_before;  // steps since output k_last
  for (std::int64_t k = 0; k < n_steps; ++k) {
    const double t = out_dt > 0.0
                         ? out_dt * static_cast<double>(k_last) + static_cast<double>(since) * h
                         : t0 + static_cast<double>(k) * h;
    ++since;
    const StepOutcome st = step(s0, t, h, s1);
    out.iterations += st.iterations;
    if (!st.converged) {
      out.converged = false;
      return out;
    }
    if (st.error > out.max_error) {
      out.max_error = st.error;
      out.t_max_error = t + h;
    }
    const bool stores = (done_before + k + 1) % out_every == 0;
    if (stores && out_yf != nullptr) {  // the step's alpha point, before y, v are replaced
      const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(out.stored);
      const double af = sc_.alpha_f;
      for (int i = 0; i < n; ++i) {
        out_yf[row * n + i] = (1.0 - af) * y1[sz(i)] + af * x.y[i];
        out_vf[row * n + i] = (1.0 - af) * v1[sz(i)] + af * x.v[i];
      }
    }
    std::copy(y1.begin(), y1.end(), x.y);
    std::copy(v1.begin(), v1.end(), x.v);
    std::copy(a1.begin(), a1.end(), x.a);
    std::copy(w1.begin(), w1.end(), x.w);
    std::copy(l1.begin(), l1.end(), x.lam);
    system_rereference(s_, x.y, x.v, x.a, x.w);
    out.steps = k + 1;
    if (stores) {
      ++k_last;
      since = 0;
      const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(out.stored);
      std::copy(x.y, x.y + n, out_y + row * n);
      std::copy(x.v, x.v + n, out_v + row * n);
      std::copy(x.lam, x.lam + m, out_l + row * m);
      if (out_e != nullptr) system_energies(s_, x.y, x.v, out_e + 3 * row, t + h);
      ++out.stored;
    }
    const std::chrono::duration<double> spent = std::chrono::steady_clock::now() - start;
    if (spent.count() >= max_seconds) return out;
  }
  return out;
}

void SystemIntegrator::constraint_curvature(const double* y, const double* v, const double* known,
                                            const double* lam, double t) {
  // c = d2/ds2 g(y + s v + s^2/2 a_known, t + s) at s = 0 into r_[n..n+m): central differences,
  // but right-sided at the run's start (t <= 0), where the motion before t = 0 is no part of the
  // run (a path table is flat there: a central difference would give half its acceleration);
  // the one-sided rule (2 g0 - 5 g1 + 4 g2 - g3) / e^2 is second order like the central one
  const int n = s_.n, m = s_.m;
  double scale = 1.0;
  for (int i = 0; i < n; ++i) scale = std::max(scale, std::abs(v[i]));
  const double e = 1e-4 / scale;
  std::vector<double> yp(sz(n)), lp(sz(m)), rate(sz(m), 0.0), g(sz(m));
  // sliding joints' material coordinates move at their rates: sigma(s) = sigma + s sigma'
  sliding_rates(s_, y, v, lam, t, rate.data());
  const bool start = t <= 0.0;
  const double at[4] = {0.0, e, start ? 2.0 * e : -e, 3.0 * e};
  const double w[4] = {start ? 2.0 : -2.0, start ? -5.0 : 1.0, start ? 4.0 : 1.0,
                       start ? -1.0 : 0.0};
  for (int i = 0; i < m; ++i) r_[sz(n + i)] = 0.0;
  for (int p = 0; p < 4; ++p) {
    if (w[p] == 0.0) continue;
    const double sp = at[p];
    for (int i = 0; i < n; ++i) yp[sz(i)] = y[i] + sp * v[i] + 0.5 * sp * sp * known[sz(i)];
    std::copy(lam, lam + m, lp.begin());
    for (int k : s_.slots) lp[sz(k)] += sp * rate[sz(k)];
    constraints(s_, yp.data(), t + sp, g.data(), lp.data());
    for (int i = 0; i < m; ++i) r_[sz(n + i)] += w[p] * g[sz(i)] / (e * e);
  }
}

bool SystemIntegrator::initial_acceleration(const double* y, const double* v, double t, double* a,
                                            double* lam, const AssemblyTerms* contact) {
  const int n = s_.n, m = s_.m;
  std::vector<double> known(sz(n), 0.0), zero(sz(m), 0.0);
  for (int k : s_.slots) zero[sz(k)] = lam[k];  // sliding joints' material coordinates
  set_prescribed(t, nullptr, nullptr, known.data());
  AssemblyTerms terms;
  terms.ck = 0.0;
  terms.cv = 0.0;
  terms.ca = 1.0;
  terms.tf = t;
  terms.t1 = t;
  if (contact != nullptr) {  // the contact state is given: no derivative by y (ck = cv = 0)
    terms.contact_yf = contact->contact_yf;
    terms.contact_vf = contact->contact_vf;
    terms.contact_y1 = contact->contact_y1;
    terms.internal = contact->internal;
    terms.own = contact->own;
  }
  lu_valid_ = false;
  const bool reuse = mass_constant_ && mass_factored_;  // the factors of M from an earlier call
  if (!assemble_system(s_, y, v, known.data(), zero.data(), y, terms, r_.data(),
                       reuse ? nullptr : &lu_))
    return false;
  if (!reuse) {
    ++factorizations_;
    mass_factored_ = lu_.factor();
    if (!mass_factored_) return false;
  }
  // acceleration-level constraints: d2/ds2 g(y + s v + s^2/2 a_known, t + s) = c + G a_free = 0
  if (m > 0) constraint_curvature(y, v, known.data(), zero.data(), t);
  solve_negative();
  for (int i = 0; i < n; ++i) a[i] = known[sz(i)] + dz_[sz(i)];
  for (int i = 0; i < m; ++i) zero[sz(i)] = dz_[sz(n + i)];
  for (int k : s_.slots) zero[sz(k)] = lam[k];
  std::copy(zero.begin(), zero.end(), lam);
  lu_valid_ = false;  // the factors are of the mass matrix
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(a[i])) return false;
  return true;
}

bool SystemIntegrator::factor_static(const double* y, const double* lam, double lf, bool amplitude,
                                     double t, double* residual, double stab) {
  AssemblyTerms terms;
  terms.tf = t;
  terms.t1 = t;
  terms.load_factor = lf;
  terms.amplitude = amplitude;
  terms.statics = true;
  lu_valid_ = false;
  const double* zero = nullptr;
  if (stab > 0.0) {  // M (0 + c 0) = 0 in the residual; stab M in the Jacobian
    zero_.assign(sz(s_.n), 0.0);
    zero = zero_.data();
    terms.ca = stab;
  }
  mass_factored_ = false;
  if (!assemble_system(s_, y, zero, zero, lam, y, terms, r_.data(), &lu_)) return false;
  std::copy(r_.begin(), r_.end(), residual);
  ++factorizations_;
  return lu_.factor();
}

void SystemIntegrator::solve_factored(double* x, double* z) {
  const int m = s_.m;
  zb_.assign(sz(lu_.border()), 0.0);
  std::copy(z, z + m, zb_.begin());
  lu_.solve(x, zb_.data());
  std::copy(zb_.begin(), zb_.begin() + m, z);
}

bool SystemIntegrator::static_increment(const double* y, const double* lam, double lf,
                                        bool amplitude, double t, double* dy, double* dlam,
                                        double* residual) {
  const int n = s_.n, m = s_.m;
  if (!factor_static(y, lam, lf, amplitude, t, residual)) return false;
  for (int i = 0; i < n; ++i) dy[i] = -residual[i];
  for (int i = 0; i < m; ++i) dlam[i] = -residual[n + i];
  solve_factored(dy, dlam);
  return true;
}

void system_energies(const System& s, const double* y, const double* v, double* out, double t) {
  const double* yref = s.y_ref;
  out[0] = out[1] = out[2] = 0.0;
  for (std::size_t b = 0; b < s.flex.size(); ++b) {
    double e[3];
    flex_energies(s, b, y, v, t, e);
    for (int i = 0; i < 3; ++i) out[i] += e[i];
  }
  for (std::size_t k = 0; k < s.rigid.size(); ++k) {
    const RigidInertia& body = s.rigid[k];
    const int o = s.rigid_offset(static_cast<int>(k));
    out[0] += rigid_kinetic_energy(body, y + o, v + o);
    const int nt = body.point_mass ? body.dim : (body.dim == 2 ? 2 : 3);
    for (int i = 0; i < nt; ++i)
      out[2] -= body.mass * s.gravity[i] * (y[o + i] - (yref != nullptr ? yref[o + i] : 0.0));
  }
  for (const SpringData& sp : s.springs) {
    PlaceEval ea, eb;
    const PlaceRef &pa = s.places[sz(sp.a)], &pb = s.places[sz(sp.b)];
    place_at(s, pa, s.maps[sz(sp.a)], 0.0, y, ea);
    place_at(s, pb, s.maps[sz(sp.b)], 0.0, y, eb);
    double len = 0.0;
    for (int i = 0; i < 3; ++i) len += (ea.x[i] - eb.x[i]) * (ea.x[i] - eb.x[i]);
    const double dl = std::sqrt(len) - sp.length;
    out[1] += sp.law < 0 ? 0.5 * sp.stiffness * dl * dl : spring_law_energy(s.tfs[sz(sp.law)], dl);
  }
  if (s.contact != nullptr) out[1] += contact_energy(s, *s.contact, y);
  if (s.winches != nullptr)  // driven drums: J(L) L'^2 / (2 r^2), the rope wound off
    for (const Winch& w : s.winches->winches)
      if (w.drum >= 0) {
        out[0] += drum_kinetic_energy(w, y, v);
        out[2] += drum_gravity_energy(w, s, y);
      }
}

void flex_energies(const System& s, std::size_t b, const double* y, const double* v, double t,
                   double* out) {
  const int o = s.offset[b];
  if (const Winch* w = winch_of(s, b)) {  // the material outside the winch at L(t)
    ScaledBody scaled;
    const WinchState st = winch_state(s, *w, t, y, v);
    const Model& mod = scaled_model(*s.flex[b], st.ratio, scaled);
    out[0] = winch_kinetic_energy(mod, *w, st, y + o, v + o);
    out[1] = strain_energy(mod, y + o);
    out[2] = winch_gravity_energy(*s.flex[b], winch_state(s, *w, 0.0), st, y + o);
    return;
  }
  const Model& mod = *s.flex[b];
  out[0] = kinetic_energy(mod, y + o, v + o);
  out[1] = strain_energy(mod, y + o);
  out[2] = gravity_energy(mod, y + o);
}

void system_rereference(const System& s, double* y, double* v, double* a, double* w) {
  thread_local std::vector<double> vw;
  for (std::size_t b = 0; b < s.flex.size(); ++b) {
    const Model& mod = *s.flex[b];
    const int o = s.offset[b];
    if (w != nullptr && kernel_for(mod).triads) {  // w's twist as a's (its own rates
      vw.assign(v + o, v + o + mod.n());           // discarded: v is carried below)
      rereference_rates(mod, y + o, vw.data(), w + o);
    }
    rereference_rates(mod, y + o, v + o, a + o);
    rereference(mod, y + o);
  }
}

}  // namespace rancf
