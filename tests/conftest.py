"""Shared tolerance tiers: each names what kind of claim a test makes.

ROUNDOFF     algebraic identities and closed forms evaluated two ways (a few hundred ulp).
QUADRATURE   integrals of the semi-analytic road done by two different quadratures, and the
             consistency identities of a solved point (closure residuals, mean pressure, edges).
LIMIT        the semi-analytic solution against an exact limit (Westergaard, Hunter) where the
             physical deviation is below it.
BEM tiers are discretisation errors: they are measured by the convergence study and written
next to that measurement in the BEM and cross-solver tests.
"""
ROUNDOFF = 1e-12
QUADRATURE = 1e-10
LIMIT = 1e-9
