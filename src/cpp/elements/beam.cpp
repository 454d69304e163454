// Planar co-rotational Euler-Bernoulli beam element (Crisfield vol. 1, sec. 7.3).
//
// Nodal coordinates (x, y, theta).  Chord d = x2 - x1, length L, chord rotation alpha from the
// reference chord (unwrapped near the mean nodal rotation):
//   eps = (L^2 - L0^2) / (2 L0^2),  tb_i = theta_i - alpha
//   U = 1/2 EA eps^2 L0 + (EI / L0)(2 tb1^2 + 2 tb1 tb2 + 2 tb2^2)
//   N = EA eps L / L0,  [M1, M2] = (EI / L0) [[4, 2], [2, 4]] [tb1, tb2]
//   f = B^T [N, M1, M2],  K = B^T D B + (N / L) z z^T + ((M1 + M2) / L^2)(r z^T + z r^T)
// with D = diag(EA (L^2 / L0^3 + eps / L0), (EI / L0)[[4, 2], [2, 4]]),
// r = [-c, -s, 0, c, s, 0], z = [s, -c, 0, -s, c, 0].
#include <algorithm>
#include <cmath>

#include "bodies/sections.hpp"
#include "elements/registry.hpp"
#include "elements/strain_rate.hpp"

namespace rancf {
namespace {

struct BeamLocal {
  double length, c, s, eps, t1, t2;
};

BeamLocal beam_local(const Model& m, int el, const double* e) {
  const double l0 = m.beam.l0[el];
  const double d0x = m.beam.d0[2 * el], d0y = m.beam.d0[2 * el + 1];
  const double dx = e[3] - e[0], dy = e[4] - e[1];
  const double length = std::sqrt(dx * dx + dy * dy);
  const double tm = 0.5 * (e[2] + e[5]);
  const double cr = std::cos(tm), sr = std::sin(tm);
  const double rx = cr * d0x - sr * d0y, ry = sr * d0x + cr * d0y;
  const double alpha = tm + std::atan2(rx * dy - ry * dx, rx * dx + ry * dy);
  const double eps = (length * length - l0 * l0) / (2.0 * l0 * l0);
  return {length, dx / length, dy / length, eps, e[2] - alpha, e[5] - alpha};
}

void beam_forces(const Model& m, int el, const double* e, double* fe, double* ke) {
  const BeamLocal b = beam_local(m, el, e);
  const double l0 = m.beam.l0[el], ea = m.stiffness.ea, ei = m.stiffness.ei;
  const double n = ea * b.eps * b.length / l0;
  const double m1 = ei / l0 * (4.0 * b.t1 + 2.0 * b.t2);
  const double m2 = ei / l0 * (2.0 * b.t1 + 4.0 * b.t2);
  const double r[6] = {-b.c, -b.s, 0.0, b.c, b.s, 0.0};
  const double z[6] = {b.s, -b.c, 0.0, -b.s, b.c, 0.0};
  double bm[3][6];
  for (int j = 0; j < 6; ++j) {
    bm[0][j] = r[j];
    bm[1][j] = -z[j] / b.length;
    bm[2][j] = -z[j] / b.length;
  }
  bm[1][2] += 1.0;
  bm[2][5] += 1.0;
  for (int j = 0; j < 6; ++j) fe[j] = bm[0][j] * n + bm[1][j] * m1 + bm[2][j] * m2;
  if (ke == nullptr) return;
  const double d00 = ea * (b.length * b.length / (l0 * l0 * l0) + b.eps / l0);
  const double k4 = 4.0 * ei / l0, k2 = 2.0 * ei / l0;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      double v = d00 * bm[0][i] * bm[0][j];
      v += k4 * (bm[1][i] * bm[1][j] + bm[2][i] * bm[2][j]);
      v += k2 * (bm[1][i] * bm[2][j] + bm[2][i] * bm[1][j]);
      v += n / b.length * z[i] * z[j];
      v += (m1 + m2) / (b.length * b.length) * (r[i] * z[j] + z[i] * r[j]);
      ke[i * 6 + j] = v;
    }
  }
}

double beam_energy(const Model& m, int el, const double* e) {
  const BeamLocal b = beam_local(m, el, e);
  const double l0 = m.beam.l0[el];
  return 0.5 * m.stiffness.ea * b.eps * b.eps * l0 +
         2.0 * m.stiffness.ei / l0 * (b.t1 * b.t1 + b.t1 * b.t2 + b.t2 * b.t2);
}

// Kelvin-Voigt strain-rate damping (docs/derivations/strain-rate-damping.md section 3, the beam):
// the axial strain eps with eps_e = L r / L0^2, eps_ee = (r r^T + z z^T) / L0^2 (dissipation
// 1/2 c_a eps'^2 L0), and the rotations tb relative to the chord, tb_i,e = B rows 1, 2 and
// tb_i,ee = (r z^T + z r^T) / L^2, whose dissipation 1/2 (c_b / L0) tb'^T [[4, 2], [2, 4]] tb' is
// the elastic law's with the rates: in the eigenvectors of [[4, 2], [2, 4]], s = (tb1 + tb2) /
// sqrt 2 (weight 6) and d = (tb1 - tb2) / sqrt 2 (weight 2), each one measure for kv_measure.
void beam_damping(const Model& m, int el, const double* e, const double* ed, double ck, double cv,
                  double* fe, double* ke) {
  const BeamLocal b = beam_local(m, el, e);
  const double l0 = m.beam.l0[el], ca = m.stiffness.damping_axial, cb = m.stiffness.damping_bending;
  const double r[6] = {-b.c, -b.s, 0.0, b.c, b.s, 0.0};
  const double z[6] = {b.s, -b.c, 0.0, -b.s, b.c, 0.0};
  double mz[6], mzz[6][6], J[6][6] = {};
  double (*jp)[6] = ke != nullptr ? J : nullptr;
  for (int i = 0; i < 6; ++i) fe[i] = 0.0;
  if (ca > 0.0) {
    const double i2 = 1.0 / (l0 * l0);
    for (int i = 0; i < 6; ++i) {
      mz[i] = b.length * r[i] * i2;
      for (int j = 0; j < 6; ++j) mzz[i][j] = (r[i] * r[j] + z[i] * z[j]) * i2;
    }
    kv_measure<6>(ca * l0, mz, mzz, ed, ck, cv, fe, jp);
  }
  if (cb > 0.0) {
    const double h = std::sqrt(0.5), il = 1.0 / b.length;
    for (int i = 0; i < 6; ++i) {  // s
      mz[i] = -2.0 * h * z[i] * il;
      for (int j = 0; j < 6; ++j) mzz[i][j] = 2.0 * h * (r[i] * z[j] + z[i] * r[j]) * il * il;
    }
    mz[2] += h;
    mz[5] += h;
    kv_measure<6>(6.0 * cb / l0, mz, mzz, ed, ck, cv, fe, jp);
    for (int i = 0; i < 6; ++i) {  // d: linear in e
      mz[i] = 0.0;
      for (int j = 0; j < 6; ++j) mzz[i][j] = 0.0;
    }
    mz[2] = h;
    mz[5] = -h;
    kv_measure<6>(2.0 * cb / l0, mz, mzz, ed, ck, cv, fe, jp);
  }
  if (ke != nullptr) std::copy(&J[0][0], &J[0][0] + 36, ke);
}

}  // namespace

const ElementKernel beam_kernel = {
    beam_forces,      beam_energy,           beam_damping,   section_beam, 2,
    /*triads=*/false, /*centre_line=*/false, /*winch=*/false};

void beam_section(const Model& m, int el, const double* e, const double* xi, int n, double* out) {
  const BeamLocal b = beam_local(m, el, e);
  const double l0 = m.beam.l0[el];
  for (int q = 0; q < n; ++q) {
    out[2 * q] = b.eps;
    out[2 * q + 1] = ((6.0 * xi[q] - 4.0) * b.t1 + (6.0 * xi[q] - 2.0) * b.t2) / l0;
  }
}

}  // namespace rancf
