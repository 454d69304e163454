// Time functions of prescribed motions, driven joints and loads: value, rate and acceleration.
//
// Kinds (every component of a vector-valued function shares the kind and its parameters):
//   constant   f(t) = c
//   piecewise  a piecewise cubic on breakpoints t_0 < ... < t_k (tables: linear or cubic spline
//              coefficients computed by the caller), held at its last value after t_k and at its
//              first before t_0
//   ramp       f(t) = c min(t / T, 1)
//   harmonic   f(t) = c sin(2 pi f t + phi)
//   spin_up    f(t) = (w / T) [t^2 / 2 + (T / 2 pi)^2 (cos(2 pi t / T) - 1)] for t <= T,
//              w (t - T / 2) after (Kane, Ryan & Banerjee 1987: the rate rises smoothly to w)
// Any kind may be built up over B: g = r f with the quintic smooth step r = 10 s^3 - 15 s^4 +
// 6 s^5, s = t / B in [0, 1] (r' = r'' = 0 at both ends), so g, g', g'' start from zero
// (rancf.bodies.time_function, T.6).
#pragma once

#include <vector>

namespace rancf {

enum class TimeKind : int { constant = 0, piecewise = 1, ramp = 2, harmonic = 3, spin_up = 4 };

struct TimeFunction {
  TimeKind kind = TimeKind::constant;
  int n = 1;                   ///< components
  std::vector<double> value;   ///< (n): c, the ramp's end value, the amplitude, the rate w
  double duration = 0.0;       ///< T (ramp, spin_up)
  double frequency = 0.0;      ///< Hz (harmonic)
  double phase = 0.0;          ///< rad (harmonic)
  double build_up = 0.0;       ///< B [s] of the smooth build-up; 0: none
  std::vector<double> breaks;  ///< (k + 1) piecewise breakpoints
  std::vector<double> coef;    ///< (k, 4, n): c0 + c1 s + c2 s^2 + c3 s^3, s = t - t_i
};

/// f, f', f'' of component comp at time t.
struct TimeValue {
  double f, df, ddf;
};

TimeValue evaluate(const TimeFunction& tf, int comp, double t);

}  // namespace rancf
