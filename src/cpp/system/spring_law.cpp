// Tabulated spring laws (spring_law.hpp): the time function's table as a tension table.
#include "system/spring_law.hpp"

namespace rancf {

namespace {

TensionTable table(const TimeFunction& f) {
  return {f.breaks.data(), f.coef.data(), static_cast<int>(f.breaks.size()) - 1};
}

}  // namespace

LawValue spring_law(const TimeFunction& law, double e) { return tension_law(table(law), e); }

double spring_law_energy(const TimeFunction& law, double e) {
  return tension_law_energy(table(law), e);
}

}  // namespace rancf
