#include "sections.hpp"

#include <array>

#include "assembly.hpp"
#include "cable.hpp"
#include "rod.hpp"

namespace rancf {

int section_width(const Model& m) { return m.kind == ElementKind::rod ? 4 : 2; }

namespace {

void cable_points(const Model& m, const SamplePoints& p, int el, const double* e, double* out) {
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

}  // namespace

void section_strains(const Model& m, const SamplePoints& p, const double* y, double* out) {
  std::array<double, kMaxElementDofs> e{};
  for (int el = 0; el < m.n_el; ++el) {
    element_coordinates(m, y, el, e.data());
    switch (m.kind) {
      case ElementKind::cable:
        cable_points(m, p, el, e.data(), out);
        break;
      case ElementKind::beam:
        beam_section(m, el, e.data(), p.xi, p.n, out + 2 * el * p.n);
        break;
      case ElementKind::rod:
        rod_point_strains(m, el, e.data(), p.n, p.xi, p.n1 + 4 * el * p.n, p.n2 + 4 * el * p.n,
                          p.ref + el * p.n, out + 4 * el * p.n);
        break;
    }
  }
}

}  // namespace rancf
