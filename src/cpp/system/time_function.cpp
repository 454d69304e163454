#include "system/time_function.hpp"

#include <algorithm>
#include <cmath>

namespace rancf {

namespace {
constexpr double kTwoPi = 6.28318530717958647692;

TimeValue plain(const TimeFunction& tf, int comp, double t) {
  const double c = tf.value[static_cast<std::size_t>(comp)];
  switch (tf.kind) {
    case TimeKind::constant:
      return {c, 0.0, 0.0};
    case TimeKind::ramp: {
      if (t >= tf.duration) return {c, 0.0, 0.0};
      if (t <= 0.0) return {0.0, 0.0, 0.0};
      return {c * t / tf.duration, c / tf.duration, 0.0};
    }
    case TimeKind::harmonic: {
      const double w = kTwoPi * tf.frequency, arg = w * t + tf.phase;
      return {c * std::sin(arg), c * w * std::cos(arg), -c * w * w * std::sin(arg)};
    }
    case TimeKind::spin_up: {
      const double tt = tf.duration;
      if (t >= tt) return {c * (t - 0.5 * tt), c, 0.0};
      const double k = kTwoPi / tt, a = tt / kTwoPi;
      return {c / tt * (0.5 * t * t + a * a * (std::cos(k * t) - 1.0)),
              c / tt * (t - a * std::sin(k * t)), c / tt * (1.0 - std::cos(k * t))};
    }
    case TimeKind::piecewise: {
      const std::size_t k = tf.breaks.size() - 1;  // intervals
      const std::size_t n = static_cast<std::size_t>(tf.n), uc = static_cast<std::size_t>(comp);
      auto at = [&](std::size_t i, double s) -> TimeValue {
        const double* p = tf.coef.data() + (i * 4) * n;
        const double c0 = p[uc], c1 = p[n + uc], c2 = p[2 * n + uc], c3 = p[3 * n + uc];
        return {c0 + s * (c1 + s * (c2 + s * c3)), c1 + s * (2.0 * c2 + 3.0 * s * c3),
                2.0 * c2 + 6.0 * s * c3};
      };
      if (t <= tf.breaks.front()) return {at(0, 0.0).f, 0.0, 0.0};
      if (t >= tf.breaks.back()) {
        const double s = tf.breaks[k] - tf.breaks[k - 1];
        return {at(k - 1, s).f, 0.0, 0.0};
      }
      const auto it = std::upper_bound(tf.breaks.begin(), tf.breaks.end(), t);
      const auto i = static_cast<std::size_t>(it - tf.breaks.begin()) - 1;
      return at(i, t - tf.breaks[i]);
    }
  }
  return {0.0, 0.0, 0.0};
}

}  // namespace

TimeValue evaluate(const TimeFunction& tf, int comp, double t) {
  const TimeValue f = plain(tf, comp, t);
  if (!(tf.build_up > 0.0) || t >= tf.build_up) return f;
  if (t <= 0.0) return {0.0, 0.0, 0.0};
  const double b = tf.build_up, s = t / b;
  const double r = s * s * s * (10.0 + s * (-15.0 + 6.0 * s));
  const double dr = 30.0 * s * s * (1.0 - s) * (1.0 - s) / b;
  const double ddr = 60.0 * s * (1.0 - s) * (1.0 - 2.0 * s) / (b * b);
  return {r * f.f, dr * f.f + r * f.df, ddr * f.f + 2.0 * dr * f.df + r * f.ddf};
}

}  // namespace rancf
