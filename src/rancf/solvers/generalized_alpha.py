"""The generalized-α integrator of a system (:mod:`rancf.solvers.dynamic` has the scheme and
the run loop): its constants, counters, the compiled core's steps and their local error
estimate (``docs/derivations/time-integration.md``)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.section_outputs import sample_points
from rancf.kernels import _core
from rancf.kernels.call_records import RunBuffers, RunOptions
from rancf.solvers.increment_scale import increment_scale
from rancf.system import System, as_system
from rancf.system.sliding import start_multipliers

__all__ = ["STRAIN_FLOOR", "GeneralizedAlpha"]

#: The least strain a body's strain error is measured against (TI.13 of
#: ``docs/derivations/time-integration.md``): a line stretched less is measured as if at 0.1 %,
#: about a steel rope's or a chain's working strain, so that a slack or unstretched body's
#: tiny strains do not set its step.
STRAIN_FLOOR = 1e-3

#: Where in each element the strain error is measured (its middle).
STRAIN_POINTS = np.array([0.5])


class GeneralizedAlpha:
    """One-step generalized-α integrator on a system (state ``y, v, a, w, λ, t``; ``w`` the
    algorithmic accelerations of the Newmark relations, Arnold & Brüls 2007).

    The Newton iterations of a step and the fixed-step loop run in the compiled core
    (:class:`rancf.kernels._core.SystemIntegrator`: constrained generalized-α, bordered band
    solves); this class holds the constants and counters.  A :class:`Model` is a one-body
    system.  ``rtol`` (> 0): a step whose estimate (TI.9) is above ``rtol * size`` reports it
    filtered through the iteration matrix (TI.12 of ``docs/derivations/time-integration.md``:
    what the step does not resolve counts as its amplitude, not ``(ω h)²`` times it); 0: never.
    ``strain_error``: the estimate measures the flexible bodies' axial strains too (TI.13).
    """

    def __init__(
        self,
        model: Model | System,
        rho_inf: float,
        newton_tol: float,
        max_newton: int,
        newton: str = "chord",
        rtol: float = 0.0,
        strain_error: bool = False,
    ) -> None:
        self.system = as_system(model)
        r = rho_inf
        self.am = (2.0 * r - 1.0) / (r + 1.0)
        self.af = r / (r + 1.0)
        self.gamma = 0.5 - self.am + self.af
        self.beta = 0.25 * (1.0 - self.am + self.af) ** 2
        size = self.system.size
        self.tol = newton_tol * size
        self.size = size
        self.max_newton = max_newton
        self.n_newton = 0
        scheme = _core.Scheme(
            alpha_m=self.am,
            alpha_f=self.af,
            gamma=self.gamma,
            beta=self.beta,
            damping=float(self.system.damping),
            tol=self.tol,
            max_iter=int(max_newton),
            modified=newton == "modified",
            chord=newton == "chord",
        )
        self._core = _core.SystemIntegrator(self.system.core, scheme)
        if self.system.contact is not None:  # a step's gap on a fixed obstacle: the blend of
            self.system.contact.step_alpha_f = self.af  # the gaps at its ends (TI.16)
        # the test measures increments as displacements (gradients times their elements' length)
        self._core.set_increment_scale(increment_scale(self.system).tolist())
        # above rtol * size a step's estimate is filtered (TI.12): what the step does not resolve
        self._core.set_error_tolerance(float(rtol) * size)
        if strain_error:
            self._strain_points()

    def _strain_points(self) -> None:
        """The estimate in the flexible bodies' axial strains too (TI.13): at every element's
        middle, relative to the body's largest strain and at least :data:`STRAIN_FLOOR`
        (beams and bodies on a winch, whose arrays hold another length, are left to the
        displacement test)."""
        system = self.system
        wound = {w.body_and_end()[0] for w in system.winches}
        for b, (name, body) in enumerate(zip(system.names, system.flex, strict=False)):
            if not body.family.gradient or name in wound:
                continue
            n1, n2, ref = sample_points(body, STRAIN_POINTS)
            self._core.add_strain_points(
                b,
                STRAIN_POINTS.tolist(),
                n1.ravel().tolist(),
                n2.ravel().tolist(),
                ref.ravel().tolist(),
                STRAIN_FLOOR,
                self.size,
            )

    @property
    def n_factorizations(self) -> int:
        """Band LU factorizations so far (Jacobians and the mass matrix)."""
        return int(self._core.factorizations)

    def memory(self) -> NDArray:
        """What the compiled loop keeps between steps: the steps since one had to start again
        from the last state (the next steps start there at once, ``docs/derivations/newton.md``)
        and, modified Newton, where its factored Jacobian was assembled."""
        return np.array(self._core.memory(), dtype=float)

    def restore(self, memory: NDArray, factorizations: int) -> None:
        """Take up :meth:`memory` of an integrator of the same system (the factors are
        assembled at the same point and factored again: the same numbers).

        Raises
        ------
        ValueError
            If the memory does not fit this system and scheme.
        """
        if not self._core.restore([float(x) for x in memory], int(factorizations)):
            raise ValueError(
                f"the integrator memory ({len(memory)} numbers) does not fit this system "
                f"and Newton method"
            )

    def prescribe(self, t: float, y: NDArray, v: NDArray) -> None:
        """Moving supports: their held coordinates and rates at ``t`` (in place)."""
        self._core.prescribe(t, y, v)

    def initial_acceleration(
        self, y: NDArray, v: NDArray, t: float, lam: NDArray | None = None
    ) -> NDArray:
        """Consistent ``a0`` (and multipliers into ``lam``): ``[M Gᵀ; G 0] [a; λ] = [-F; -c]``."""
        a = np.empty(self.system.n)
        lam = start_multipliers(self.system) if lam is None else lam
        self._core.initial_acceleration(y, v, t, a, lam)
        return a

    def step(
        self,
        y: NDArray,
        v: NDArray,
        a: NDArray,
        w: NDArray,
        t: float,
        h: float,
        lam: NDArray | None = None,
    ) -> tuple[bool, NDArray, NDArray, NDArray, NDArray, float]:
        """Advance by ``h``; returns ``(converged, y1, v1, a1, w1, error)``, ``error`` the
        step's local error estimate (:meth:`relative_error`: in units of the tolerance ``rtol *
        size`` once divided by it; 0 if it did not converge).  The new multipliers replace
        ``lam``'s content when it converged."""
        y1, v1, a1, w1 = (np.empty_like(y) for _ in range(4))
        l0 = start_multipliers(self.system) if lam is None else lam
        l1 = np.empty_like(l0)
        ok, it, err = self._core.step(y, v, a, w, l0, t, h, y1, v1, a1, w1, l1)
        if ok and lam is not None:
            lam[:] = l1
        self.n_newton += it
        return ok, y1, v1, a1, w1, err

    def run_steps(
        self,
        y: NDArray,
        v: NDArray,
        a: NDArray,
        w: NDArray,
        t: float,
        h: float,
        n_steps: int,
        per_out: int,
        done_before: int = 0,
        max_seconds: float = np.inf,
        lam: NDArray | None = None,
        out_dt: float = 0.0,
        k_last: int = 0,
        energies: bool = True,
    ) -> tuple:
        """Fixed steps in the core from time ``t`` (``y, v, a, w``, ``lam`` updated in place).

        ``out_dt > 0``: the steps' times are ``out_dt k + i h``, ``k`` the index of the last
        output (``k_last`` at the start) and ``i`` the steps since it, so that a run's numbers
        do not depend on where it was cut into calls (a resumed run's neither).

        An output is stored every ``per_out`` steps of an output interval, whose first already
        holds ``done_before`` steps.  The core returns early, after a whole step, once
        ``max_seconds`` of wall time have passed (so that the caller can poll for interrupts).
        Returns ``(steps done, status, iterations, outputs stored, out_y, out_v, out_e,
        out_l, out_alpha, error, t_error)``; status is 1 if every step taken converged, else 0
        (the failing step is not taken); ``out_alpha`` (systems with contact, else None): each
        stored row's step's generalized-α point ``(y_f, v_f)`` side by side, ``(n_out, 2 n)``,
        where its contact forces act; ``error`` the largest local error estimate of the steps
        taken (length, as :meth:`step`'s) and ``t_error`` the time at the end of that step;
        ``out_e`` is None without ``energies`` (a sink that derives them from the rows).
        """
        n, m = self.system.n, self.system.m
        n_out = (done_before + n_steps) // per_out
        oy, ov = np.empty((n_out, n)), np.empty((n_out, n))
        oe = np.empty((n_out, 3)) if energies else None
        ol = np.empty((n_out, m))
        contact = self.system.has_contact
        of = (np.empty((n_out, n)), np.empty((n_out, n))) if contact else (None, None)
        lam = np.zeros(m) if lam is None else lam
        done, ok, iters, stored, err, t_err = self._core.run(
            RunBuffers(y, v, a, w, lam, oy, ov, ol, oe, *of),
            RunOptions(t, h, n_steps, per_out, done_before, max_seconds, out_dt, k_last),
        )
        oa = np.concatenate(of, axis=1) if contact else None  # type: ignore[arg-type]
        self.n_newton += iters
        return done, int(ok), iters, stored, oy, ov, oe, ol, oa, err, t_err

    def alpha_point(self, y0: NDArray, v0: NDArray, y1: NDArray, v1: NDArray) -> NDArray:
        """``(y_{n+1-α_f}, v_{n+1-α_f})`` of a step from ``(y0, v0)`` to ``(y1, v1)``, side by
        side ``(2 n,)``: where the step's contact forces act."""
        af = self.af
        return np.concatenate([(1.0 - af) * y1 + af * y0, (1.0 - af) * v1 + af * v0])

    def relative_error(self, error: float, rtol: float) -> float:
        """A local error estimate of :meth:`step` or :meth:`run_steps` relative to the
        tolerance ``rtol * size`` (``e = h² |β - γ/2 + 1/12| max_i s_i |w_{n+1,i} - w_{n,i}|``,
        ``s_i`` the Newton test's increment scale: (TI.9) of
        ``docs/derivations/time-integration.md``; above the tolerance given at construction,
        the filtered (TI.12))."""
        return error / (rtol * self.size)
