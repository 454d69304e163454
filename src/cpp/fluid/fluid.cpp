// Fluid loads on lines (fluid.hpp; docs/derivations/fluid.md).
#include "fluid/fluid.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "bodies/assembly.hpp"
#include "elements/registry.hpp"

namespace rancf {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::size_t sz(int i) { return static_cast<std::size_t>(i); }

/// cosh(k (zs + h)) / sinh(k h) and sinh(k (zs + h)) / sinh(k h), zs <= 0 (deep water: exp(k zs)).
void depth_ratios(double k, double h, double zs, double& cr, double& sr) {
  if (k * h > 25.0) {
    cr = sr = std::exp(k * zs);
    return;
  }
  const double s = std::sinh(k * h);
  cr = std::cosh(k * (zs + h)) / s;
  sr = std::sinh(k * (zs + h)) / s;
}

/// Component i's phase k_i x - omega_i t - phi_i at x along the direction of travel.
double wave_phase(const Waves& w, std::size_t i, double x, double t) {
  return w.k[i] * x - w.omega[i] * t - w.phase[i];
}

/// Component i's Airy velocity and acceleration, and their derivatives with respect to r, at
/// phase th and depth zs below the still surface (above: held at it) added to out.
void add_airy(const Waves& w, std::size_t i, double th, double zs, bool above, int zi,
              FluidPoint& out) {
  const double c = std::cos(th), s = std::sin(th), dz = above ? 0.0 : 1.0;
  double cr = 0.0, sr = 0.0;
  depth_ratios(w.k[i], w.depth, zs, cr, sr);
  const double a = w.amplitude[i] * w.omega[i], om = w.omega[i], k = w.k[i];
  const double uh = a * cr * c, uv = a * sr * s;
  const double duh = a * om * cr * s, duv = -a * om * sr * c;
  for (int j = 0; j < zi; ++j) {
    out.u[j] += uh * w.dir[j];
    out.du[j] += duh * w.dir[j];
  }
  out.u[zi] += uv;
  out.du[zi] += duv;
  // derivatives of (uh, uv, duh, duv) along the direction (d th / d r_j = k dir_j) and in z
  const double uh_x = -a * cr * s * k, uh_z = a * k * sr * c * dz;
  const double uv_x = a * sr * c * k, uv_z = a * k * cr * s * dz;
  const double duh_x = a * om * cr * c * k, duh_z = a * om * k * sr * s * dz;
  const double duv_x = a * om * sr * s * k, duv_z = -a * om * k * cr * c * dz;
  for (int j = 0; j < zi; ++j) {
    for (int l = 0; l < zi; ++l) {
      out.u_r[l][j] += uh_x * w.dir[l] * w.dir[j];
      out.du_r[l][j] += duh_x * w.dir[l] * w.dir[j];
    }
    out.u_r[zi][j] += uv_x * w.dir[j];
    out.du_r[zi][j] += duv_x * w.dir[j];
    out.u_r[j][zi] += uh_z * w.dir[j];
    out.du_r[j][zi] += duh_z * w.dir[j];
  }
  out.u_r[zi][zi] += uv_z;
  out.du_r[zi][zi] += duv_z;
}

/// Offset in an element's coordinates of its position/gradient block k (0: rA, 1: rA', 2: rB,
/// 3: rB'): cables k dim, rods as rod_common.hpp (a twist after each node's gradient).
int block_offset(const Model& m, int k) {
  if (kernel_for(m).triads) {
    constexpr int off[4] = {0, 3, 7, 10};
    return off[k];
  }
  return k * m.dim;
}

}  // namespace

void fluid_point(const FluidField& f, int dim, const double* r, double t, bool waves,
                 FluidPoint& out) {
  out = FluidPoint{};
  const int zi = dim - 1;
  const double z = r[zi];
  const std::size_t np = f.profile_z.size();
  if (np > 0) {  // linear in height between the rows, constant beyond them
    if (z <= f.profile_z[0] || np == 1) {
      for (int i = 0; i < 3; ++i) out.u[i] = f.profile_u[sz(i)];
    } else if (z >= f.profile_z[np - 1]) {
      for (int i = 0; i < 3; ++i) out.u[i] = f.profile_u[3 * (np - 1) + sz(i)];
    } else {
      std::size_t k = 0;
      while (f.profile_z[k + 1] < z) ++k;
      const double h = f.profile_z[k + 1] - f.profile_z[k], s = (z - f.profile_z[k]) / h;
      for (int i = 0; i < 3; ++i) {
        const double u0 = f.profile_u[3 * k + sz(i)], u1 = f.profile_u[3 * (k + 1) + sz(i)];
        out.u[i] = u0 + s * (u1 - u0);
        out.u_r[i][zi] = (u1 - u0) / h;
      }
    }
  } else {
    for (int i = 0; i < 3; ++i) out.u[i] = f.current[i];
  }
  double eta = f.surface;
  if (waves && f.waves.on) {
    const Waves& w = f.waves;
    double x = 0.0;
    for (int j = 0; j < zi; ++j) x += r[j] * w.dir[j];
    const bool above = z > f.surface;  // above the still surface: the values at it
    const double zs = above ? 0.0 : z - f.surface;
    for (std::size_t i = 0; i < w.amplitude.size(); ++i) {
      const double th = wave_phase(w, i, x, t);
      eta += w.amplitude[i] * std::cos(th);
      if (w.k[i] > 0.0) add_airy(w, i, th, zs, above, zi, out);
    }
  }
  out.wet = !f.has_surface || z < eta;
}

double surface_elevation(const FluidField& f, int dim, const double* r, double t) {
  double eta = f.surface;
  if (!f.waves.on) return eta;
  const Waves& w = f.waves;
  double x = 0.0;
  for (int j = 0; j < dim - 1; ++j) x += r[j] * w.dir[j];
  for (std::size_t i = 0; i < w.amplitude.size(); ++i)
    eta += w.amplitude[i] * std::cos(wave_phase(w, i, x, t));
  return eta;
}

namespace {

// assemble_line's terms of one element at a time, with the dimension a constant (the small
// loops unrolled): set up once a call, then element() for each element (on any thread).
template <int dim>
struct LineElements {
  const Model& m;
  const FluidSet& fs;
  const LineFluid& line;
  const double *y, *v, *acc;
  const LineTerms& tm;
  const FluidField& fl;
  bool dynamic, moves, uniform;
  double rho, d, area, cn, ct, lf;
  double load[3] = {0.0, 0.0, 0.0};  // the distributed loads at time t
  int off[4] = {0, 0, 0, 0};
  FluidPoint fp0;  // a uniform fluid's kinematics (fluid_point's values at every point)

  LineElements(const Model& m_, const FluidSet& fs_, const LineFluid& line_, const double* y_,
               const double* v_, const double* acc_, const LineTerms& tm_)
      : m(m_), fs(fs_), line(line_), y(y_), v(v_), acc(acc_), tm(tm_), fl(fs_.field) {
    dynamic = acc != nullptr;
    rho = fl.density;
    d = line.diameter;
    area = 0.25 * kPi * d * d;
    cn = 0.5 * rho * d * line.cdn;
    ct = 0.5 * rho * kPi * d * line.cdt;
    lf = tm.load_factor;
    // the derivatives along positions and rates count (the mass matrix alone needs neither)
    moves = tm.ck != 0.0 || tm.cv != 0.0;
    for (const DistributedLoad& ld : line.loads) {
      const double fac = ld.factor >= 0 ? evaluate((*tm.tfs)[sz(ld.factor)], 0, tm.t).f : 1.0;
      for (int i = 0; i < 3; ++i) load[i] += lf * fac * ld.force[i];
    }
    for (int k = 0; k < 4; ++k) off[k] = block_offset(m, k);
    // the fluid's kinematics do not depend on the point: set once
    uniform = fl.profile_z.empty() && !(dynamic && fl.waves.on);
    if (uniform)
      for (int i = 0; i < 3; ++i) fp0.u[i] = fl.current[i];
  }

  /// A driven drum's share at one Gauss point (DrumFluid): its residual -c f.a and, if de is
  /// not null, the derivative of it in the element's coordinates into de; A, B the force's
  /// derivatives in r (with v, acc) and a = r' (ck d/dy + cv d/dv + ca d/dacc).
  void drum_point(double c, const double* f, const double* a, const double (&A)[3][3],
                  const double (&B)[3][3], const double* S, const double* S1, double* de) const {
    double fa = 0.0;
    for (int i = 0; i < dim; ++i) fa += f[i] * a[i];
    tm.drum->residual -= c * fa;
    if (de == nullptr) return;
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < dim; ++i) {
        double g = tm.ck * f[i] * S1[k];  // d a / dy
        for (int j = 0; j < dim; ++j) g += a[j] * (A[j][i] * S[k] + B[j][i] * S1[k]);
        de[sz(off[k] + i)] -= c * g;
      }
  }

  /// Element el's force fe and, if ke is not null, its Jacobian ke (both written whole);
  /// force (if not null) += the fluid's force on it; a drum's share (tm.drum) of it into de
  /// (written whole, if not null) and tm.drum->residual.
  void element(int el, double* fe, double* ke, double* force, double* de = nullptr) const {
    const int nde = m.nde(), nq = line.n_qp;
    std::array<double, kMaxElementDofs> e{}, ev{}, ea{};
    FluidPoint fp = fp0;
    gather_element(m, el, y, e.data());
    gather_element(m, el, v, ev.data());
    gather_element(m, el, acc, ea.data());
    std::fill(fe, fe + kMaxElementDofs, 0.0);
    if (de != nullptr) std::fill(de, de + kMaxElementDofs, 0.0);
    if (ke != nullptr) std::fill(ke, ke + kMaxElementDofs * kMaxElementDofs, 0.0);
    for (int q = 0; q < nq; ++q) {
      const std::size_t iq = sz(el * nq + q);
      const double* S = line.n0.data() + 4 * iq;
      const double* S1 = line.n1.data() + 4 * iq;
      const double w = line.gw[sz(q)] * line.j0[iq] * tm.length_ratio;
      double x[3] = {}, a[3] = {}, vel[3] = {}, ac[3] = {};
      for (int k = 0; k < 4; ++k)
        for (int i = 0; i < dim; ++i) {
          x[i] += S[k] * e[sz(off[k] + i)];
          a[i] += S1[k] * e[sz(off[k] + i)];
          vel[i] += S[k] * ev[sz(off[k] + i)];
          ac[i] += S[k] * ea[sz(off[k] + i)];
        }
      double f[3] = {load[0], load[1], load[2]};
      // the force's derivative: A = ck d/dr + cv d/dv + ca d/dacc, B = ck d/da
      double A[3][3] = {}, B[3][3] = {};
      if (!line.hydro) {
      } else if (uniform) {  // a uniform current, no waves: u, no du, no gradients
        fp.wet = !fl.has_surface || x[dim - 1] < fl.surface;
      } else {
        fluid_point(fl, dim, x, tm.t, dynamic, fp);
      }
      if (line.hydro && fp.wet) {
        double fx[3] = {0.0, 0.0, 0.0};  // the fluid's force (no loads)
        // the normal part wn = w - (w.a / a.a) a and |a| as two independent chains (each one
        // square root), not one after the other through t
        double la2 = 0.0, wa = 0.0, wv[3] = {0.0, 0.0, 0.0}, wn[3] = {0.0, 0.0, 0.0};
        for (int i = 0; i < dim; ++i) {
          wv[i] = fp.u[i] - vel[i];
          la2 += a[i] * a[i];
          wa += wv[i] * a[i];
        }
        const double sa = wa / la2, inv_la = 1.0 / std::sqrt(la2);
        double nn = 0.0;
        for (int i = 0; i < dim; ++i) {
          wn[i] = wv[i] - sa * a[i];
          nn += wn[i] * wn[i];
        }
        nn = std::sqrt(nn);
        const double wt = wa * inv_la;
        double t[3] = {0.0, 0.0, 0.0};
        for (int i = 0; i < dim; ++i) t[i] = a[i] * inv_la;
        const double awt = std::abs(wt);
        for (int i = 0; i < dim; ++i)
          fx[i] += lf * (cn * nn * wn[i] + ct * awt * wt * t[i]) - lf * rho * area * fs.gravity[i];
        double hh[3] = {0.0, 0.0, 0.0}, th = 0.0;
        const double ra = rho * area, dc = line.cat - line.can;
        if (dynamic) {  // Froude-Krylov and added mass
          for (int i = 0; i < dim; ++i) {
            hh[i] = dc * (fp.du[i] - ac[i]);
            th += t[i] * hh[i];
          }
          for (int i = 0; i < dim; ++i)
            fx[i] += ra * ((1.0 + line.can) * fp.du[i] - line.can * ac[i] + t[i] * th);
        }
        if (ke != nullptr && moves) {
          // d f_D / d w = G and d f_D / d t (w held) = Ft in closed form (fluid.md section 4):
          // with wn normal to t, d(|wn| wn)/d wn = dn = |wn| I + wn wn^T / |wn| gives
          // dn (I - t t^T) = dn - |wn| t t^T and dn (t w^T + wt I) = |wn| t w^T + wt dn; the
          // axial part 2 |wt| t (d wt) + |wt| wt (d t)
          const double inv_nn = nn > 0.0 ? 1.0 / nn : 0.0;
          double G[3][3], Ft[3][3], Ftt[3] = {0.0, 0.0, 0.0};
          for (int i = 0; i < dim; ++i)
            for (int j = 0; j < dim; ++j) {
              const double id = i == j ? 1.0 : 0.0, tt = t[i] * t[j];
              const double dn = nn * id + wn[i] * wn[j] * inv_nn;
              G[i][j] = lf * (2.0 * ct * awt * tt + cn * (dn - nn * tt));
              Ft[i][j] = lf * (ct * awt * (2.0 * t[i] * wv[j] + wt * id) -
                               cn * (nn * t[i] * wv[j] + wt * dn));
              if (dynamic) Ft[i][j] += ra * (th * id + t[i] * hh[j]);
              Ftt[i] += Ft[i][j] * t[j];
              A[i][j] = -tm.cv * G[i][j];
            }
          if (!uniform)  // through the fluid's kinematics at r
            for (int i = 0; i < dim; ++i)
              for (int j = 0; j < dim; ++j) {
                double fr = 0.0;
                for (int l = 0; l < dim; ++l) {
                  fr += G[i][l] * fp.u_r[l][j];
                  if (dynamic) {
                    const double id = i == l ? 1.0 : 0.0;
                    fr += ra * ((1.0 + line.can) * id + dc * t[i] * t[l]) * fp.du_r[l][j];
                  }
                }
                A[i][j] += tm.ck * fr;
              }
          for (int i = 0; i < dim; ++i)  // d t / d a = (I - t t^T) / |a|
            for (int j = 0; j < dim; ++j) B[i][j] = tm.ck * (Ft[i][j] - Ftt[i] * t[j]) * inv_la;
        }
        if (ke != nullptr && dynamic)  // the added mass
          for (int i = 0; i < dim; ++i)
            for (int j = 0; j < dim; ++j)
              A[i][j] -= tm.ca * ra * (line.can * (i == j ? 1.0 : 0.0) + dc * t[i] * t[j]);
        for (int i = 0; i < dim; ++i) {
          f[i] += fx[i];
          if (force != nullptr) force[i] += w * fx[i];
        }
      }
      for (int k = 0; k < 4; ++k)
        for (int i = 0; i < dim; ++i) fe[sz(off[k] + i)] -= w * S[k] * f[i];
      if (tm.drum != nullptr) drum_point(tm.drum->c[iq], f, a, A, B, S, S1, de);
      if (ke == nullptr || !line.hydro || !fp.wet) continue;  // loads alone: no derivative
      for (int k = 0; k < 4; ++k) {  // the block (k, l): -w S_k (A S_l + B S'_l)
        const double wk = w * S[k];
        for (int l = 0; l < 4; ++l) {
          const double al = wk * S[l], be = wk * S1[l];
          for (int i = 0; i < dim; ++i)
            for (int j = 0; j < dim; ++j)
              ke[sz((off[k] + i) * nde + off[l] + j)] -= al * A[i][j] + be * B[i][j];
        }
      }
    }
  }
};

template <int dim>
void line_terms(const void* ctx, int el, double* fe, double* ke) {
  static_cast<const LineElements<dim>*>(ctx)->element(el, fe, ke, nullptr);
}

// assemble_line with the dimension a constant; shared between threads unless the fluid's force
// is summed or a drum's share taken (their sums in element order, point by point, on one
// thread).
template <int dim>
void line_forces(const Model& m, const FluidSet& fs, const LineFluid& line, const double* y,
                 const double* v, const double* acc, const LineTerms& tm, double* r,
                 const BandView* jac, double* force) {
  const LineElements<dim> le(m, fs, line, y, v, acc, tm);
  if (force == nullptr && tm.drum == nullptr &&
      add_elements_shared(m, line_terms<dim>, &le, r, jac, 1.0))
    return;
  std::array<double, kMaxElementDofs> fe{}, de{};
  std::array<double, kMaxElementDofs * kMaxElementDofs> ke{};
  double* row = tm.drum != nullptr ? tm.drum->row : nullptr;
  for (int el = 0; el < m.n_el; ++el) {
    le.element(el, fe.data(), jac != nullptr ? ke.data() : nullptr, force,
               row != nullptr ? de.data() : nullptr);
    scatter_element(m, el, fe.data(), jac != nullptr ? ke.data() : nullptr, r, jac, 1.0);
    if (row != nullptr) scatter_element(m, el, de.data(), nullptr, row, nullptr, 1.0);
  }
}

}  // namespace

void assemble_line(const Model& m, const FluidSet& fs, const LineFluid& line, const double* y,
                   const double* v, const double* acc, const LineTerms& tm, double* r,
                   const BandView* jac, double* force) {
  if (m.dim == 2)
    line_forces<2>(m, fs, line, y, v, acc, tm, r, jac, force);
  else
    line_forces<3>(m, fs, line, y, v, acc, tm, r, jac, force);
}

}  // namespace rancf
