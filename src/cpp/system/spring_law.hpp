// A spring's tension law T(e) of its stretch e = l - length (rancf.system.parts.spring): a
// piecewise cubic in the form of a time function's table (TimeKind::piecewise, one component,
// the stretch in place of the time), continued linearly with its end slopes beyond its first and
// last breakpoints (elements/tension_law.hpp evaluates it).  The linear spring-damper has no law
// (T = k e).
#pragma once

#include "elements/tension_law.hpp"
#include "system/time_function.hpp"

namespace rancf {

/// The law's tension and its slope at the stretch e.
LawValue spring_law(const TimeFunction& law, double e);

/// The law's strain energy: the integral of T from 0 to e (exact for the cubic pieces).
double spring_law_energy(const TimeFunction& law, double e);

}  // namespace rancf
