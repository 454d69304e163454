#include "bodies/assembly.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "bodies/threads.hpp"
#include "elements/registry.hpp"
#include "elements/rod.hpp"

namespace rancf {

// Rotated blocks of supported nodes (a roller's position, a clamp's gradient): e <- T e (to q)
// for the element's two nodes.  Block b of node a starts at a dpn + b dim.
void rotate_to_q(const Model& m, int el, double* e) {
  const int d = m.dim;
  for (int a = 0; a < 2; ++a) {
    for (int blk = 0; blk < 2; ++blk) {
      const std::int64_t r = m.supports.rot_of_node[2 * (el + a) + blk];
      if (r < 0) continue;
      const double* bas = m.supports.rot + r * d * d;
      double* g = e + a * m.dpn + blk * d;
      double tmp[3] = {0.0, 0.0, 0.0};
      for (int i = 0; i < d; ++i)
        for (int j = 0; j < d; ++j) tmp[i] += bas[i * d + j] * g[j];
      for (int i = 0; i < d; ++i) g[i] = tmp[i];
    }
  }
}

// f <- T^T f and K <- T^T K T for the element's rotated blocks.
void rotate_block_back(const Model& m, const double* bas, int o, double* fe, double* ke) {
  const int d = m.dim, nde = m.nde();
  double tmp[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j) tmp[i] += bas[j * d + i] * fe[o + j];
  for (int i = 0; i < d; ++i) fe[o + i] = tmp[i];
  if (ke == nullptr) return;
  for (int c = 0; c < nde; ++c) {  // rows
    double t[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < d; ++i)
      for (int j = 0; j < d; ++j) t[i] += bas[j * d + i] * ke[(o + j) * nde + c];
    for (int i = 0; i < d; ++i) ke[(o + i) * nde + c] = t[i];
  }
  for (int c = 0; c < nde; ++c) {  // columns
    double t[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < d; ++i)
      for (int j = 0; j < d; ++j) t[i] += ke[c * nde + o + j] * bas[j * d + i];
    for (int i = 0; i < d; ++i) ke[c * nde + o + i] = t[i];
  }
}

void rotate_back(const Model& m, int el, double* fe, double* ke) {
  for (int a = 0; a < 2; ++a)
    for (int blk = 0; blk < 2; ++blk) {
      const std::int64_t r = m.supports.rot_of_node[2 * (el + a) + blk];
      if (r >= 0)
        rotate_block_back(m, m.supports.rot + r * m.dim * m.dim, a * m.dpn + blk * m.dim, fe, ke);
    }
}

bool has_rotation(const Model& m, int el) {
  for (int i = 0; i < 4; ++i)
    if (m.supports.rot_of_node[2 * el + i] >= 0) return true;
  return false;
}

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

void gather_element(const Model& m, int el, const double* x, double* e) {
  const int nde = m.nde();
  if (x == nullptr) {
    std::fill(e, e + nde, 0.0);
    return;
  }
  if (m.reduced()) {
    const Reduction& r = m.reduction;
    const double* xs = x + r.el_start[el];
    const double* E = r.el_map + static_cast<std::ptrdiff_t>(el) * nde * r.width;
    for (int i = 0; i < nde; ++i) {
      double v = 0.0;
      for (int j = 0; j < r.width; ++j) v += E[i * r.width + j] * xs[j];
      e[i] = v;
    }
    return;
  }
  if (m.connectivity.nodes_of != nullptr) {  // node by node, q_k = B^T y_k at supported nodes
    const int dpn = m.dpn;
    const std::int64_t* nodes = m.connectivity.nodes_of + std::ptrdiff_t{el} * m.connectivity.nodes;
    for (int a = 0; a < m.connectivity.nodes; ++a) {
      const double* xa = x + nodes[a] * dpn;
      double* ea = e + a * dpn;
      const std::int64_t r = m.shell.node_rot[nodes[a]];
      if (r < 0) {
        std::copy(xa, xa + dpn, ea);
        continue;
      }
      const double* bas = m.shell.node_basis + r * dpn * dpn;
      for (int i = 0; i < dpn; ++i) {
        double v = 0.0;
        for (int j = 0; j < dpn; ++j) v += bas[j * dpn + i] * xa[j];
        ea[i] = v;
      }
    }
    return;
  }
  const int base = el * m.dpn;
  std::copy(x + base, x + base + nde, e);
  if (has_rotation(m, el)) rotate_to_q(m, el, e);
}

namespace {

/// A connected element's force and matrix to model coordinates at its supported nodes:
/// fe_a <- B fe_a, ke <- T ke T^T with T = diag(B_a) (B_a the identity at other nodes).
void rotate_connected(const Model& m, const std::int64_t* nodes, double* fe, double* ke) {
  const int nn = m.connectivity.nodes, dpn = m.dpn, nde = m.nde();
  std::array<double, kMaxAssemblyDofs> t{};
  for (int a = 0; a < nn; ++a) {
    const std::int64_t r = m.shell.node_rot[nodes[a]];
    if (r < 0) continue;
    const double* bas = m.shell.node_basis + r * dpn * dpn;
    const int o = a * dpn;
    auto turn = [&](double* v, std::ptrdiff_t stride) {  // v <- B v (dpn values, stride apart)
      for (int i = 0; i < dpn; ++i) {
        double s = 0.0;
        for (int j = 0; j < dpn; ++j) s += bas[i * dpn + j] * v[j * stride];
        t[static_cast<std::size_t>(i)] = s;
      }
      for (int i = 0; i < dpn; ++i) v[i * stride] = t[static_cast<std::size_t>(i)];
    };
    turn(fe + o, 1);
    if (ke == nullptr) continue;
    for (int c = 0; c < nde; ++c) turn(ke + o * nde + c, nde);  // rows of block a
    for (int c = 0; c < nde; ++c) turn(ke + c * nde + o, 1);    // columns of block a
  }
}

/// scatter_element of a model with a connectivity: node blocks added where they belong.
void scatter_connected(const Model& m, int el, const double* fe_q, const double* ke_q, double* f,
                       const BandView* k, double k_scale) {
  const int nn = m.connectivity.nodes, dpn = m.dpn, nde = m.nde();
  const std::int64_t* nodes = m.connectivity.nodes_of + std::ptrdiff_t{el} * nn;
  const double *fe = fe_q, *ke = ke_q;
  bool turned = false;
  for (int a = 0; a < nn; ++a) turned = turned || m.shell.node_rot[nodes[a]] >= 0;
  thread_local std::vector<double> g, kk;
  if (turned) {
    g.assign(fe_q, fe_q + nde);
    if (ke_q != nullptr) kk.assign(ke_q, ke_q + static_cast<std::ptrdiff_t>(nde) * nde);
    rotate_connected(m, nodes, g.data(), ke_q != nullptr ? kk.data() : nullptr);
    fe = g.data();
    ke = ke_q != nullptr ? kk.data() : nullptr;
  }
  for (int a = 0; a < nn; ++a)
    for (int i = 0; i < dpn; ++i) f[nodes[a] * dpn + i] += fe[a * dpn + i];
  if (k == nullptr || ke == nullptr) return;
  for (int b = 0; b < nn; ++b)
    for (int j = 0; j < dpn; ++j) {
      const int col = static_cast<int>(nodes[b]) * dpn + j;
      for (int a = 0; a < nn; ++a) {
        const int row = static_cast<int>(nodes[a]) * dpn;
        double* c = &k->at(row, col);
        const double* kr = ke + static_cast<std::ptrdiff_t>(a * dpn) * nde + b * dpn + j;
        for (int i = 0; i < dpn; ++i) c[i * k->rs] += k_scale * kr[i * nde];
      }
    }
}

}  // namespace

void scatter_element(const Model& m, int el, const double* fe, const double* ke, double* f,
                     const BandView* k, double k_scale) {
  if (m.connectivity.nodes_of != nullptr) {
    scatter_connected(m, el, fe, ke, f, k, k_scale);
    return;
  }
  const int nde = m.nde();
  const bool matrix = k != nullptr && ke != nullptr;
  if (m.reduced()) {
    const Reduction& r = m.reduction;
    const int s = static_cast<int>(r.el_start[el]), w = r.width;
    const double* E = r.el_map + static_cast<std::ptrdiff_t>(el) * nde * w;
    for (int j = 0; j < w; ++j) {
      double v = 0.0;
      for (int i = 0; i < nde; ++i) v += E[i * w + j] * fe[i];
      f[s + j] += v;
    }
    if (!matrix) return;
    std::array<double, kMaxElementDofs * kMaxWindow> kt{};  // ke E (nde x w)
    for (int i = 0; i < nde; ++i)
      for (int j = 0; j < w; ++j) {
        double v = 0.0;
        for (int a = 0; a < nde; ++a) v += ke[i * nde + a] * E[a * w + j];
        kt[static_cast<std::size_t>(i * w + j)] = v;
      }
    for (int j = 0; j < w; ++j) {
      double* colj = &k->at(s, s + j);
      for (int i = 0; i < w; ++i) {
        double v = 0.0;
        for (int a = 0; a < nde; ++a) v += E[a * w + i] * kt[static_cast<std::size_t>(a * w + j)];
        colj[i * k->rs] += k_scale * v;
      }
    }
    return;
  }
  const int base = el * m.dpn;
  std::array<double, kMaxElementDofs> g{};
  std::array<double, kMaxElementDofs * kMaxElementDofs> kk{};
  std::copy(fe, fe + nde, g.begin());
  if (matrix) std::copy(ke, ke + nde * nde, kk.begin());
  if (has_rotation(m, el)) rotate_back(m, el, g.data(), matrix ? kk.data() : nullptr);
  for (int i = 0; i < nde; ++i) f[base + i] += g[static_cast<std::size_t>(i)];
  if (!matrix) return;
  for (int j = 0; j < nde; ++j) {
    double* colj = &k->at(base, base + j);  // A(base + i, base + j) = colj[(i) * rs]
    for (int i = 0; i < nde; ++i)
      colj[i * k->rs] += k_scale * kk[static_cast<std::size_t>(i * nde + j)];
  }
}

void scatter_node(const Model& m, int node, const double* g, double* f) {
  const Reduction& r = m.reduction;
  const int s = static_cast<int>(r.node_start[node]), w = r.node_width;
  const double* N = r.node_map + static_cast<std::ptrdiff_t>(node) * m.dpn * w;
  for (int j = 0; j < w; ++j) {
    double v = 0.0;
    for (int i = 0; i < m.dpn; ++i) v += N[i * w + j] * g[i];
    f[s + j] += v;
  }
}

int twist_index(const Model& m, int node) {
  return m.reduced() ? static_cast<int>(m.reduction.twist[node]) : node * m.dpn + 6;
}

namespace {

/// The width of an element's terms in the shared loop's buffers: fe, then ke (width x width
/// values, of which the kernel writes nde x nde) at fe + width; a line element's terms may fill
/// the whole kMaxElementDofs (the fluid's), a shell's are 48.
std::ptrdiff_t term_width(const Model& m) { return std::max(m.nde(), kMaxElementDofs); }

/// One element loop shared between threads (bodies/threads.hpp): chunk 0's elements are
/// added by the calling thread as they come, the other chunks' forces and tangents kept in
/// `out` (one stride a element, from element `kept`) and added afterwards in element order.
struct ElementLoop {
  const Model& m;
  ElementTerms terms;
  const void* ctx;
  double* f;
  const BandView* k;
  double k_scale;
  int n_chunks, kept;
  std::ptrdiff_t stride;
  double* out;

  [[nodiscard]] int first(int c) const {
    return static_cast<int>(std::int64_t{m.n_el} * c / n_chunks);
  }

  void chunk(int c) const {
    thread_local std::vector<double> own;
    own.assign(static_cast<std::size_t>(stride), 0.0);  // zero once, as the array it replaced
    for (int el = first(c); el < first(c + 1); ++el) {
      double* fe = c == 0 ? own.data() : out + (el - kept) * stride;
      double* ke = k == nullptr ? nullptr : fe + term_width(m);
      terms(ctx, el, fe, ke);
      if (c == 0) scatter_element(m, el, fe, ke, f, k, k_scale);
    }
  }
};

void run_chunk(void* loop, int c) { static_cast<const ElementLoop*>(loop)->chunk(c); }

struct KernelTerms {
  const Model& m;
  const ElementKernel& kern;
  const double* y;
};

void kernel_terms(const void* ctx, int el, double* fe, double* ke) {
  const auto& kt = *static_cast<const KernelTerms*>(ctx);
  std::array<double, kMaxAssemblyDofs> e{};
  gather_element(kt.m, el, kt.y, e.data());
  kt.kern.forces(kt.m, el, e.data(), fe, ke);
}

}  // namespace

bool add_elements_shared(const Model& m, ElementTerms terms, const void* ctx, double* f,
                         const BandView* k, double k_scale) {
  const int threads = assembly_threads();
  if (threads < 2 || m.n_el < kMinParallelElements) return false;
  thread_local std::vector<double> out;
  const std::ptrdiff_t w = term_width(m), stride = k != nullptr ? w * (w + 1) : w;
  ElementLoop loop{m, terms, ctx, f, k, k_scale, threads, 0, stride, nullptr};
  loop.kept = loop.first(1);
  out.resize(static_cast<std::size_t>((m.n_el - loop.kept) * stride));
  loop.out = out.data();
  if (!run_chunks(threads, run_chunk, &loop)) return false;
  for (int el = loop.kept; el < m.n_el; ++el) {
    const double* fe = loop.out + (el - loop.kept) * stride;
    scatter_element(m, el, fe, k != nullptr ? fe + w : nullptr, f, k, k_scale);
  }
  return true;
}

void assemble(const Model& m, const double* y, double* f, const BandView* k, double k_scale) {
  const ElementKernel& kern = kernel_for(m);
  const int n = m.n();
  std::fill(f, f + n, 0.0);
  const KernelTerms kt{m, kern, y};
  if (add_elements_shared(m, kernel_terms, &kt, f, k, k_scale)) return;
  std::array<double, kMaxAssemblyDofs> e{}, fe{};
  thread_local std::vector<double> ke;
  ke.assign(static_cast<std::size_t>(term_width(m) * term_width(m)), 0.0);
  double* kep = k != nullptr ? ke.data() : nullptr;
  for (int el = 0; el < m.n_el; ++el) {
    gather_element(m, el, y, e.data());
    kern.forces(m, el, e.data(), fe.data(), kep);
    scatter_element(m, el, fe.data(), kep, f, k, k_scale);
  }
}

void assemble_damping(const Model& m, const double* y, const double* v, double ck, double cv,
                      double* f, const BandView* k) {
  const ElementKernel& kern = kernel_for(m);
  if (!m.stiffness.strain_rate_damping() || kern.damping == nullptr) return;
  std::array<double, kMaxElementDofs> e{}, ed{}, fe{};
  std::array<double, kMaxElementDofs * kMaxElementDofs> ke{};
  double* kep = k != nullptr ? ke.data() : nullptr;
  for (int el = 0; el < m.n_el; ++el) {
    gather_element(m, el, y, e.data());
    gather_element(m, el, v, ed.data());
    kern.damping(m, el, e.data(), ed.data(), ck, cv, fe.data(), kep);
    scatter_element(m, el, fe.data(), kep, f, k, 1.0);
  }
}

double strain_energy(const Model& m, const double* y) {
  const ElementKernel& kern = kernel_for(m);
  std::array<double, kMaxAssemblyDofs> e{};
  double total = 0.0;
  for (int el = 0; el < m.n_el; ++el) {
    gather_element(m, el, y, e.data());
    total += kern.energy(m, el, e.data());
  }
  return total;
}

void element_coordinates(const Model& m, const double* y, int el, double* e) {
  gather_element(m, el, y, e);
}

void nodal_gradient(const Model& m, const double* y, int node, double* rx) {
  const int d = m.dim;
  if (m.reduced()) {
    const Reduction& r = m.reduction;
    const double* ys = y + r.node_start[node];
    const double* N = r.node_map + static_cast<std::ptrdiff_t>(node) * m.dpn * r.node_width;
    for (int i = 0; i < d; ++i) {
      double v = 0.0;
      for (int j = 0; j < r.node_width; ++j) v += N[(d + i) * r.node_width + j] * ys[j];
      rx[i] = v;
    }
    return;
  }
  const double* g = y + node * m.dpn + d;
  const std::int64_t r = m.supports.rot_of_node[2 * node + 1];
  for (int i = 0; i < d; ++i) rx[i] = g[i];
  if (r < 0) return;
  const double* bas = m.supports.rot + r * d * d;
  for (int i = 0; i < d; ++i) {
    rx[i] = 0.0;
    for (int j = 0; j < d; ++j) rx[i] += bas[i * d + j] * g[j];
  }
}

namespace {

double load_factor(double freq, double t, bool amplitude) {
  return (freq > 0.0 && !amplitude) ? std::sin(2.0 * kPi * freq * t) : 1.0;
}

// Moment p at its node: generalized force g (4) on (r_x, phi) in model coordinates and, if kl,
// its derivative (4 x 4) with respect to the model coordinates (r_x, phi) of that node.
void moment_terms(const Model& m, int p, double t, const double* y, bool amplitude, double* g,
                  double* kl) {
  const int node = static_cast<int>(m.loads.moment_node[p]);
  const double fac = load_factor(m.loads.moment_freq[p], t, amplitude);
  double mom[3], rx[3];
  for (int i = 0; i < 3; ++i) mom[i] = fac * m.loads.moment[3 * p + i];
  nodal_gradient(m, y, node, rx);
  rod_moment_load(m, node, mom, rx, g, kl);
  const std::int64_t r = m.supports.rot_of_node[2 * node + 1];
  if (r < 0) return;
  const double* bas = m.supports.rot + r * 9;  // q = T y on the r_x block: map g and kl back
  double tmp[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) tmp[i] += bas[j * 3 + i] * g[j];
  for (int i = 0; i < 3; ++i) g[i] = tmp[i];
  if (kl == nullptr) return;
  double k2[16];
  for (int i = 0; i < 4; ++i)  // kl_y = T4^T kl_q T4, T4 = diag(bas, 1)
    for (int j = 0; j < 4; ++j) {
      double v = 0.0;
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
          const double ta = a < 3 ? (i < 3 ? bas[a * 3 + i] : 0.0) : (i == 3 ? 1.0 : 0.0);
          const double tb = b < 3 ? (j < 3 ? bas[b * 3 + j] : 0.0) : (j == 3 ? 1.0 : 0.0);
          v += ta * kl[a * 4 + b] * tb;
        }
      k2[i * 4 + j] = v;
    }
  for (int i = 0; i < 16; ++i) kl[i] = k2[i];
}

}  // namespace

void external_force(const Model& m, double t, const double* y, double* f, bool amplitude) {
  const int n = m.n();
  std::copy(m.loads.f_gravity, m.loads.f_gravity + n, f);
  for (int p = 0; p < m.loads.n_point; ++p) {
    const double fac = load_factor(m.loads.freq[p], t, amplitude);
    if (m.reduced()) {  // base = node dpn: the node's force through its map
      double g[kMaxElementDofs] = {};
      for (int i = 0; i < m.dim; ++i) g[i] = m.loads.f0[p * m.dim + i] * fac;
      scatter_node(m, static_cast<int>(m.loads.base[p]) / m.dpn, g, f);
      continue;
    }
    for (int i = 0; i < m.dim; ++i) f[m.loads.base[p] + i] += m.loads.f0[p * m.dim + i] * fac;
  }
  for (int p = 0; p < m.loads.n_moment; ++p) {
    double g[4];
    moment_terms(m, p, t, y, amplitude, g, nullptr);
    const int node = static_cast<int>(m.loads.moment_node[p]);
    if (m.reduced()) {  // g on (r_x, phi) = q entries 3..6 of the node
      double gq[kMaxElementDofs] = {};
      for (int i = 0; i < 4; ++i) gq[3 + i] = g[i];
      scatter_node(m, node, gq, f);
      continue;
    }
    const int o = node * m.dpn + 3;
    for (int i = 0; i < 4; ++i) f[o + i] += g[i];
  }
}

void subtract_load_stiffness(const Model& m, double t, const double* y, const BandView& k,
                             double scale, bool amplitude) {
  for (int p = 0; p < m.loads.n_moment; ++p) {
    double g[4], kl[16];
    moment_terms(m, p, t, y, amplitude, g, kl);
    const int node = static_cast<int>(m.loads.moment_node[p]);
    if (m.reduced()) {  // N_s^T kl N_s over the node's window (N_s: rows 3..6 of its map)
      const Reduction& r = m.reduction;
      const int s = static_cast<int>(r.node_start[node]), w = r.node_width;
      const double* N = r.node_map + static_cast<std::ptrdiff_t>(node) * m.dpn * w + 3 * w;
      for (int i = 0; i < w; ++i)
        for (int j = 0; j < w; ++j) {
          double v = 0.0;
          for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b) v += N[a * w + i] * kl[a * 4 + b] * N[b * w + j];
          if (v != 0.0) k.at(s + i, s + j) -= scale * v;
        }
      continue;
    }
    const int o = node * m.dpn + 3;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) k.at(o + i, o + j) -= scale * kl[i * 4 + j];
  }
}

void rereference(const Model& m, const double* y) {
  if (!kernel_for(m).triads) return;
  std::array<double, 3> rx{};
  for (int node = 0; node < m.n_nodes; ++node) {
    nodal_gradient(m, y, node, rx.data());
    double* tr = m.rod.tref + 3 * node;
    double* mr = m.rod.m1ref + 3 * node;
    double t3[3], u[3];
    rod_nodal_triad(tr, mr, rx.data(), 0.0, t3, u);
    for (int i = 0; i < 3; ++i) {
      tr[i] = t3[i];
      mr[i] = u[i];
    }
  }
  if (m.closed) {  // the last node is the first: the same reference triad to the last bit
    const int last = m.n_nodes - 1;
    for (int i = 0; i < 3; ++i) {
      m.rod.tref[3 * last + i] = m.rod.tref[i];
      m.rod.m1ref[3 * last + i] = m.rod.m1ref[i];
    }
  }
}

}  // namespace rancf
