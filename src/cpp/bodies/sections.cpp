#include "bodies/sections.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "bodies/assembly.hpp"
#include "elements/cable.hpp"
#include "elements/registry.hpp"
#include "elements/rod.hpp"

namespace rancf {

int section_width(const Model& m) { return kernel_for(m).section_width; }

void section_cable(const Model& m, const SamplePoints& p, int el, const double* e, double* out) {
  const int d = m.dim;
  for (int q = 0; q < p.n; ++q) {
    const int k = el * p.n + q;
    double a[3] = {0.0, 0.0, 0.0}, b[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < d; ++i)
      for (int j = 0; j < 4; ++j) {
        a[i] += p.n1[4 * k + j] * e[j * d + i];
        b[i] += p.n2[4 * k + j] * e[j * d + i];
      }
    const QpGeometry g = cable_qp_geometry(a, b, d);
    out[2 * k] = green_lagrange(g.aa, p.ref[k]);
    out[2 * k + 1] = g.kappa;
  }
}

void section_beam(const Model& m, const SamplePoints& p, int el, const double* e, double* out) {
  beam_section(m, el, e, p.xi, p.n, out + 2 * el * p.n);
}

void section_rod(const Model& m, const SamplePoints& p, int el, const double* e, double* out) {
  rod_point_strains(m, el, e, p.n, p.xi, p.n1 + 4 * el * p.n, p.n2 + 4 * el * p.n, p.ref + el * p.n,
                    out + 4 * el * p.n);
}

void section_strains(const Model& m, const SamplePoints& p, const double* y, double* out) {
  const ElementKernel& kernel = kernel_for(m);
  std::array<double, kMaxElementDofs> e{};
  for (int el = 0; el < m.n_el; ++el) {
    element_coordinates(m, y, el, e.data());
    kernel.section(m, p, el, e.data(), out);
  }
}

void section_forces(int k, int n_points, int w, const double* raw, const double* kappa0,
                    const double* c, double ea, bool engineering, const TensionTable& law,
                    const double* scale, double* out) {
  const int nk = w - 1;
  for (int i = 0; i < k; ++i) {
    const double sc = scale[i];
    for (int p = 0; p < n_points; ++p) {
      const std::ptrdiff_t at = static_cast<std::ptrdiff_t>(i) * n_points + p;
      const double* r = raw + at * w;
      double* o = out + at * 2 * w;
      const double eps = r[0], lam = std::sqrt(std::max(1.0 + 2.0 * eps, 0.0));
      double bend = 0.0;
      o[0] = eps;
      for (int j = 0; j < nk; ++j) {
        const double kap = r[1 + j];
        const double mom = c[j] * (kap - kappa0[p * nk + j] / sc) / lam;
        o[2 + j] = kap;
        o[2 + nk + j] = mom;
        bend += mom * kap;
      }
      const double axial =
          law.active() ? tension_law(law, lam - 1.0).t : ea * (engineering ? lam - 1.0 : eps * lam);
      o[1] = axial - bend;
    }
  }
}

}  // namespace rancf
