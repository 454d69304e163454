#include "elements/registry.hpp"

#include <stdexcept>

namespace rancf {

const ElementKernel& kernel_for(const Model& m) {
  switch (m.kind) {
    case ElementKind::cable:
      return m.dim == 2 ? cable2d_kernel : cable3d_kernel;
    case ElementKind::beam:
      return beam_kernel;
    case ElementKind::rod:
      return rod_kernel;
    case ElementKind::shell:
      return shell_kernel;
  }
  throw std::invalid_argument("unknown element kind");
}

}  // namespace rancf
