"""Independent reference solutions for the tests (numpy/scipy only; nothing from rancf).

Each reference is computed by a method that shares no code and no discretization with rancf
(shooting on the differential equations of the rod, quadrature, closed forms), so agreement with
rancf is evidence, not a tautology.  ``tests/test_references.py`` checks them against known
closed-form results and their own convergence.
"""
