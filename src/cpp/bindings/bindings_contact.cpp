// Python bindings of contact (rancf._core.Contact): copies the arrays into the named structs of
// contact.hpp, checks sizes, forwards.
#include "bindings/bindings_contact.hpp"

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <vector>

#include "contact/body_contact.hpp"

namespace rancf_bind {

using namespace nb::literals;

namespace {

void check(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(what);
}

const rancf::System& system_of(const ContactHolder& h) {
  if (h.sys == nullptr) throw std::invalid_argument("contact: not attached to a system");
  return *h.sys;
}

const double* opt(const std::optional<In>& a, std::size_t n, const char* name) {
  if (!a) return nullptr;
  expect_size(*a, n, name);
  return a->data();
}

}  // namespace

void bind_contact(nb::module_& mod) {
  mod.attr("CONTACT_OUTPUTS") = rancf::kContactOutputs;
  nb::class_<ContactHolder>(mod, "Contact", "Obstacles and contact pairs (see contact.hpp).")
      .def(
          "__init__",
          [](ContactHolder* h, nb::list body_nc, nb::list body_radius, nb::list body_n,
             nb::list body_n1, nb::list body_gw, nb::list body_w, InI ob_kind, InI ob_body,
             In ob_point, In ob_dir, In ob_radius, InI pair_flex, InI pair_obstacle, In pair_data,
             nb::list body_weights, nb::list body_scales, nb::list body_arc0, InI bpair_a,
             InI bpair_b, In bpair_data) {
            new (h) ContactHolder();
            rancf::ContactSet& c = h->c;
            const std::size_t nbody = body_nc.size();
            check(body_radius.size() == nbody && body_n.size() == nbody &&
                      body_n1.size() == nbody && body_gw.size() == nbody && body_w.size() == nbody,
                  "contact bodies: lists of one length");
            for (std::size_t b = 0; b < nbody; ++b) {
              rancf::ContactBody cb;
              cb.n_c = nb::cast<int>(body_nc[b]);
              cb.radius = nb::cast<double>(body_radius[b]);
              const In n = nb::cast<In>(body_n[b]), n1 = nb::cast<In>(body_n1[b]);
              const In gw = nb::cast<In>(body_gw[b]), w = nb::cast<In>(body_w[b]);
              expect_size(gw, static_cast<std::size_t>(cb.n_c), "body_gw");
              check(n.size() == 4 * w.size() && n1.size() == n.size(),
                    "contact bodies: N, N1 (n_el, n_c, 4) and w (n_el, n_c)");
              cb.N.assign(n.data(), n.data() + n.size());
              cb.N1.assign(n1.data(), n1.data() + n1.size());
              cb.gw.assign(gw.data(), gw.data() + gw.size());
              cb.w.assign(w.data(), w.data() + w.size());
              if (body_weights.size() == nbody) {  // curves for contact between bodies
                const In wt = nb::cast<In>(body_weights[b]), sc = nb::cast<In>(body_scales[b]);
                const In a0 = nb::cast<In>(body_arc0[b]);
                check(wt.size() == 4 * sc.size() && (sc.size() == 0 || a0.size() == sc.size() + 1),
                      "contact bodies: weights (n_el, 4), scales (n_el), arc0 (n_el + 1)");
                cb.weights.assign(wt.data(), wt.data() + wt.size());
                cb.scales.assign(sc.data(), sc.data() + sc.size());
                cb.arc0.assign(a0.data(), a0.data() + a0.size());
              }
              c.bodies.push_back(std::move(cb));
            }
            const std::size_t no = ob_kind.size();
            expect_size(ob_body, no, "ob_body");
            expect_size(ob_point, 3 * no, "ob_point");
            expect_size(ob_dir, 3 * no, "ob_dir");
            expect_size(ob_radius, no, "ob_radius");
            for (std::size_t i = 0; i < no; ++i) {
              rancf::Obstacle ob;
              check(ob_kind.data()[i] >= 0 && ob_kind.data()[i] <= 2, "ob_kind: 0, 1 or 2");
              ob.kind = static_cast<rancf::ObstacleKind>(ob_kind.data()[i]);
              ob.body = static_cast<int>(ob_body.data()[i]);
              for (int k = 0; k < 3; ++k) {
                ob.point[k] = ob_point.data()[3 * i + static_cast<std::size_t>(k)];
                ob.dir[k] = ob_dir.data()[3 * i + static_cast<std::size_t>(k)];
              }
              ob.radius = ob_radius.data()[i];
              c.obstacles.push_back(ob);
            }
            const std::size_t np = pair_flex.size();
            expect_size(pair_obstacle, np, "pair_obstacle");
            expect_size(pair_data, 6 * np, "pair_data");
            for (std::size_t i = 0; i < np; ++i) {
              rancf::ContactPair cp;
              cp.flex = static_cast<int>(pair_flex.data()[i]);
              cp.obstacle = static_cast<int>(pair_obstacle.data()[i]);
              check(cp.flex >= 0 && static_cast<std::size_t>(cp.flex) < nbody,
                    "pair_flex: no such body");
              check(cp.obstacle >= 0 && static_cast<std::size_t>(cp.obstacle) < no,
                    "pair_obstacle: no such obstacle");
              const double* d = pair_data.data() + 6 * i;
              cp.stiffness = d[0];
              cp.onset = d[1];
              cp.damping = d[2];
              cp.friction = d[3];
              cp.slip_velocity = d[4];
              cp.damping_normal = d[5];
              check(cp.stiffness > 0.0 && cp.onset > 0.0 && cp.slip_velocity > 0.0,
                    "pair_data: stiffness, onset and slip velocity > 0");
              c.pairs.push_back(cp);
            }
            const std::size_t nbp = bpair_a.size();
            expect_size(bpair_b, nbp, "bpair_b");
            expect_size(bpair_data, 4 * nbp, "bpair_data");
            for (std::size_t i = 0; i < nbp; ++i) {
              rancf::BodyPair bp;
              bp.a = static_cast<int>(bpair_a.data()[i]);
              bp.b = static_cast<int>(bpair_b.data()[i]);
              for (int x : {bp.a, bp.b})
                check(x >= 0 && static_cast<std::size_t>(x) < nbody &&
                          !c.bodies[static_cast<std::size_t>(x)].scales.empty(),
                      "bpair: a body with contact curves");
              const double* d = bpair_data.data() + 4 * i;
              bp.stiffness = d[0];
              bp.onset = d[1];
              bp.friction = d[2];
              bp.slip_velocity = d[3];
              check(bp.stiffness > 0.0 && bp.onset > 0.0 && bp.friction >= 0.0 &&
                        bp.slip_velocity > 0.0,
                    "bpair_data: stiffness, onset, slip velocity > 0, friction >= 0");
              c.body_pairs.push_back(bp);
            }
          },
          nb::kw_only(), "body_nc"_a, "body_radius"_a, "body_n"_a, "body_n1"_a, "body_gw"_a,
          "body_w"_a, "ob_kind"_a, "ob_body"_a, "ob_point"_a, "ob_dir"_a, "ob_radius"_a,
          "pair_flex"_a, "pair_obstacle"_a, "pair_data"_a, "body_weights"_a, "body_scales"_a,
          "body_arc0"_a, "bpair_a"_a, "bpair_b"_a, "bpair_data"_a)
      .def_prop_rw(
          "step_alpha_f", [](const ContactHolder& h) { return h.c.step_alpha_f; },
          [](ContactHolder& h, double af) {
            check(af >= 0.0 && af < 1.0, "step_alpha_f: a number in [0, 1)");
            h.c.step_alpha_f = af;
          },
          "alpha_f of the time steps whose alpha points the contact forces are given at: a "
          "point's gap of a step is the blend of its gaps at the step's ends (0: the "
          "gap at the alpha point).")
      .def(
          "body_outputs",
          [](const ContactHolder& h, In y, Out out) {
            const rancf::System& s = system_of(h);
            expect_size(y, static_cast<std::size_t>(s.n), "y");
            expect_size(out, rancf::kBodyOutputs * h.c.body_pairs.size(), "out");
            rancf::body_contact_outputs(s, h.c, y.data(), out.data());
          },
          "y"_a, "out"_a.noconvert(),
          "Per body pair: smallest gap of the candidates, points in contact, total normal force.")
      .def(
          "energy",
          [](const ContactHolder& h, In y) {
            const rancf::System& s = system_of(h);
            expect_size(y, static_cast<std::size_t>(s.n), "y");
            return rancf::contact_energy(s, h.c, y.data());
          },
          "y"_a, "The penalty's potential energy at y.")
      .def(
          "outputs",
          [](const ContactHolder& h, In y, std::optional<In> v, Out out, std::optional<In> y1) {
            const rancf::System& s = system_of(h);
            const auto n = static_cast<std::size_t>(s.n);
            expect_size(y, n, "y");
            expect_size(out, rancf::kContactOutputs * h.c.obstacles.size(), "out");
            rancf::contact_outputs(s, h.c, y.data(), opt(v, n, "v"), opt(y1, n, "y1"), out.data());
          },
          "y"_a, "v"_a.none(), "out"_a.noconvert(), "y1"_a.none() = nb::none(),
          "Per obstacle: normal force (3), friction force (3), moment (3), contact length, "
          "largest penetration; with y1: (y, v) a time step's alpha point, y1 its end, the "
          "forces the step applies.")
      .def(
          "points",
          [](const ContactHolder& h, int k, In y, std::optional<In> v, Out out) {
            const rancf::System& s = system_of(h);
            const auto n = static_cast<std::size_t>(s.n);
            expect_size(y, n, "y");
            if (k < 0 || static_cast<std::size_t>(k) >= h.c.pairs.size())
              throw std::invalid_argument("points: no such pair");
            const rancf::ContactPair& cp = h.c.pairs[static_cast<std::size_t>(k)];
            const rancf::ContactBody& cb = h.c.bodies[static_cast<std::size_t>(cp.flex)];
            expect_size(out, 8 * cb.w.size(), "out");
            rancf::contact_points(s, h.c, k, y.data(), opt(v, n, "v"), out.data());
          },
          "k"_a, "y"_a, "v"_a.none(), "out"_a.noconvert(),
          "Pair k's points: position (3), gap, pressure, friction force (3).")
      .def(
          "assemble",
          [](const ContactHolder& h, In yf, std::optional<In> vf, In y1, double ck, double cv,
             Out r, std::optional<Out> jac) {
            const rancf::System& s = system_of(h);
            const auto n = static_cast<std::size_t>(s.n);
            expect_size(yf, n, "yf");
            expect_size(y1, n, "y1");
            expect_size(r, n, "r");
            if (jac) expect_size(*jac, n * n, "jac");
            rancf::AssemblyTerms tm;
            tm.ck = ck;
            tm.cv = cv;
            std::fill(r.data(), r.data() + n, 0.0);
            double* dense = jac ? jac->data() : nullptr;
            if (dense != nullptr) std::fill(dense, dense + n * n, 0.0);
            const rancf::MatrixSink sink = [&](const int* idx, int k, const double* K) {
              for (int a = 0; a < k; ++a)
                for (int b = 0; b < k; ++b)
                  dense[static_cast<std::size_t>(idx[a]) * n + static_cast<std::size_t>(idx[b])] +=
                      K[a * k + b];
            };
            // the same state twice is one array: the pressure at yf
            const bool same = std::equal(yf.data(), yf.data() + n, y1.data());
            rancf::assemble_contact(s, h.c, yf.data(), opt(vf, n, "vf"),
                                    same ? yf.data() : y1.data(), tm, r.data(), nullptr,
                                    dense != nullptr ? &sink : nullptr);
          },
          "yf"_a, "vf"_a.none(), "y1"_a, "ck"_a, "cv"_a, "r"_a.noconvert(),
          "jac"_a.none() = nb::none(),
          "The contact terms alone (for checks): r = -(generalized contact forces) at (yf, vf) "
          "with the step's mean pressure up to y1, and their Jacobian with respect to y1, ck "
          "d/dyf + cv d/dvf + d/dy1, dense (n x n).");
}

}  // namespace rancf_bind
