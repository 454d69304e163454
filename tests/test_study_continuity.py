"""What C² buys, the reduced study: the shipped cantilever's bending
frequencies and the 6.1 pendulum's tip, C¹ against C² (rancf.studies.continuity; the full
study's table is in docs/guide/closed-curves.md and benchmarks/results/continuity_study.json)."""

from __future__ import annotations

import numpy as np

from rancf.studies.continuity import continuity_study


def test_reduced_continuity_study():
    doc = continuity_study(quick=True)
    cant = {(r["continuity"], r["elements"]): r for r in doc["cantilever"]}
    for r in doc["cantilever"]:  # every first frequency from above (a Rayleigh-Ritz bound)
        assert r["errors"][0] > 0
    c1, c2 = cant["C1", 8], cant["C2", 8]
    assert (c1["unknowns"], c2["unknowns"]) == (33, 19)
    # the accuracy of C¹ on the first two frequencies with 58 % of its unknowns ...
    assert np.all(np.abs(c2["errors"][:2]) < 1.15 * np.abs(c1["errors"][:2]))
    # ... and half its highest frequency (the stiffest mode a step must resolve)
    assert c2["highest_hz"] < 0.55 * c1["highest_hz"]
    # per element C² is the coarser space: the fifth frequency is worse at 8 elements
    assert abs(c2["errors"][4]) > abs(c1["errors"][4])
    pend = {(r["continuity"], r["elements"]): r for r in doc["pendulum"]}
    # the pendulum tip: C² with 28 unknowns beats C¹ with 26 (both on 0.2 s)
    assert pend["C2", 12]["unknowns"] == 28 and pend["C1", 6]["unknowns"] == 26
    assert pend["C2", 12]["tip_error"] < 0.5 * pend["C1", 6]["tip_error"]
    assert doc["pendulum_reference_check"] < 0.5 * pend["C2", 12]["tip_error"]
