"""A mesh study: `solve_meshes`, the BEM on several fixed meshes with their grids solved once (the
surface's `bem.solve_surface_meshes` checks its meshes with `_meshes` too)."""
from __future__ import annotations

from dataclasses import replace

from viscosine.checks import bad, positive_int

from ._solver import (_announced, _elastic_starts, _grids_result, _level, _Problem, _problem,
                      _Run, _sizes)


def solve_meshes(*, nodes, load=None, penetration=None, speed, profile=None, material=None,
                 ratio=None, hk=None, tol=1e-10, max_outer=50, restart=8, max_inner=300,
                 layer=None):
    """A mesh study: `solve` on each fixed mesh of ``nodes``, the grids solved once.

    Fixed meshes solved one by one solve their coarser grids again each time (a study of
    N = 2^10 ... 2^18 costs about 3.8 solves of its finest grid); here they are one nested
    sequence from the coarsest mesh's first grid up, each grid started from the one half as
    fine (about 2).  Each result is what ``solve(nodes=N, ...)`` answers: its grid started from
    N/2, its estimate from the grids N/8 ... N.  The differences lie below N/8, where ``solve``
    jumps by quarters to start its grids, and in the retries of a first grid that failed (the
    study's first grid has them, not the grids it starts from there): the answers agree to the
    Krylov tolerance ``tol``, not bit for bit.  Where both solve the same grids (the coarsest
    mesh, and up to N = 4096 when the coarsest is 1024) they are the same bits.

    Parameters
    ----------
    nodes : sequence of int
        The meshes, distinct, each at least 8 panels and the finest divided by a power of two
        (one nested sequence); given in any order, answered coarse to fine.
    load, penetration, speed, profile, material, ratio, hk, tol, max_outer, restart, max_inner, layer
        As for `solve`.

    Returns
    -------
    iterator of BemResult
        One per mesh, coarse to fine, each yielded as soon as its grid is solved (a caller can
        show progress); ``list(...)`` for all.  The inputs are checked before the first.

    Raises
    ------
    ValueError
        On bad input, naming the parameter, its value and what is allowed.
    """
    meshes = _meshes(nodes)
    p = _problem(load=load, penetration=penetration, speed=speed, profile=profile,
                 material=material, ratio=ratio, hk=hk, nodes=meshes[-1], rtol=None,
                 max_nodes=None, tol=tol, max_outer=max_outer, restart=restart,
                 max_inner=max_inner, nested=True, layer=layer)
    return (_announced(r) for r in _study(p, meshes))


def _meshes(nodes) -> list:
    """The meshes of `solve_meshes`, checked, coarse to fine."""
    if isinstance(nodes, (str, bytes)) or not hasattr(nodes, "__iter__"):
        raise bad("nodes", nodes, "a sequence of meshes (integers >= 8)")
    given = [positive_int("nodes", n, 8) for n in nodes]
    meshes = sorted(set(given))
    if not meshes:
        raise bad("nodes", nodes, "at least one mesh (integers >= 8)")
    if len(meshes) != len(given):
        raise bad("nodes", nodes, "distinct meshes (each answered once)")
    top = meshes[-1]
    for n in meshes:
        q, r = divmod(top, n)
        if r or q & (q - 1):
            raise bad("nodes", nodes, f"meshes that halve the finest in turn ({top}/{n} is not a "
                      "power of two): one nested sequence of grids")
    return meshes


def _study(p: _Problem, meshes: list):
    """The grids of every mesh of ``meshes`` (p.nodes the finest): halvings from the finest
    down to the coarsest mesh's own first grid (`_sizes`), the result of each mesh taken as its
    grid is solved (`_grids_result` as on that fixed mesh)."""
    run = _Run()
    elastic, harmonic = _elastic_starts(p)
    low = _sizes(replace(p, nodes=meshes[0]))[0]
    n, sizes = p.nodes, []
    while n >= low:
        sizes.append(n)
        n //= 2
    for n in reversed(sizes):
        _level(p, run, n, elastic, harmonic)  # a fixed mesh: no window, never stopped
        if n in meshes:
            yield _grids_result(replace(p, nodes=n), run)
