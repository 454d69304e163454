// Kelvin-Voigt strain-rate damping of one strain measure (docs/derivations/strain-rate-damping.md
// section 2): the one implementation of eqs. (2)-(5), used by every element kernel that has it
// (cable.cpp, beam.cpp, rod_damping.hpp) with its own measures.
#pragma once

namespace rancf {

/// One strain measure m(z) with damping coefficient c (times the length element): with mz =
/// dm/dz, mzz = d2m/dz2 and zd = dz/dt, the rate md = mz . zd (eq. 2), the force c md mz added
/// into g (eq. 3) and, if jz, ck c (mz (mzz zd)^T + md mzz) + cv c mz mz^T added into jz (eqs. 4,
/// 5; row: force, column: z).
template <int NZ>
inline void kv_measure(double c, const double* mz, const double (*mzz)[NZ], const double* zd,
                       double ck, double cv, double* g, double (*jz)[NZ]) {
  double md = 0.0, hz[NZ];
  for (int i = 0; i < NZ; ++i) md += mz[i] * zd[i];
  for (int i = 0; i < NZ; ++i) g[i] += c * md * mz[i];
  if (jz == nullptr) return;
  for (int i = 0; i < NZ; ++i) {
    hz[i] = 0.0;
    for (int j = 0; j < NZ; ++j) hz[i] += mzz[i][j] * zd[j];
  }
  for (int i = 0; i < NZ; ++i)
    for (int j = 0; j < NZ; ++j)
      jz[i][j] += c * (ck * (mz[i] * hz[j] + md * mzz[i][j]) + cv * mz[i] * mz[j]);
}

}  // namespace rancf
