"""The report's document: its parts written out as Markdown and rendered to HTML (`Doc`), the
number formats of its tables (`_fmt`, `_reldiff`), the versions it states, its figures' paths
and the texts every section shares (`PAPER`, `TAMAAS_MISSING`).  Part of `comparisons.report`,
which re-exports it.
"""
from __future__ import annotations

import math
import os
import platform
from dataclasses import dataclass, field

import numpy as np

from . import _html

# ---------------------------------------------------------------------------- the document
@dataclass
class Doc:
    """The report as a list of parts, written out as Markdown; the HTML page is that Markdown
    rendered by `comparisons._html` (one text, two renderings: report.html is report.md)."""

    parts: list = field(default_factory=list)  # ("h", level, text) | ("p", text) | ("table", head, rows) | ("img", file, caption)

    def h(self, level, text):
        self.parts.append(("h", level, text))

    def p(self, text):
        self.parts.append(("p", text))

    def table(self, head, rows):
        self.parts.append(("table", head, rows))

    def img(self, name, caption):
        self.parts.append(("img", name, caption))

    def markdown(self):
        out = []
        for part in self.parts:
            if part[0] == "h":
                out.append("#" * part[1] + " " + part[2] + "\n")
            elif part[0] == "p":
                out.append(part[1] + "\n")
            elif part[0] == "table":
                out.append(_html.table(part[1], part[2]))  # escapes a '|' inside a cell
            else:
                out.append(f"![{part[2]}]({part[1]})\n")
        return "\n".join(out)

    def html(self, folder):
        """The offline page: report.md rendered, its images embedded (read from ``folder``)."""
        return _html.render(self.markdown(), folder, title="viscosine cross-validation")


def _fmt(v, digits=6):
    if v is None:
        return "—"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float) and not math.isfinite(v):
        return "—"
    return f"{v:.{digits}g}"


def _reldiff(a, b):
    if a is None or b is None:
        return "—"
    return f"{abs(a - b) / max(abs(b), 1e-300):.2e}"


def _versions():
    from importlib.metadata import version

    import numba
    import scipy
    try:
        vis = version("viscosine")
    except Exception:  # pragma: no cover - running from a source tree without install
        vis = "source tree"
    return {"viscosine": vis, "python": platform.python_version(), "numpy": np.__version__,
            "scipy": scipy.__version__, "numba": numba.__version__,
            "matplotlib": version("matplotlib")}  # its version, without importing it


def _png(folder, name):
    """Where the figure ``name`` is written (the document links it as ``name.png``)."""
    return os.path.join(folder, f"{name}.png")


PAPER = ("Menga, Putignano, Carbone & Demelio, The sliding contact of a rigid wavy surface with a "
         "viscoelastic half-space, Proc. R. Soc. A 470, 20140392 (2014)")


#: what a report without the third code says, in its Tamaas section and at its top
TAMAAS_MISSING = (
    "Tamaas is not installed here, so this section has no results: everything else in this "
    "report stands on its own (both roads, the paper's figures, fields, agreement, convergence). "
    "Tamaas 2.9 is the extra `peers`. From a clone of the repository (the README's first "
    "command installs `.` without it) run `pip install '.[peers]'` in the same environment "
    "(from PyPI: `pip install 'viscosine[peers]'`; the test extra `'.[test]'` includes it), "
    "then the same report command again with `--resume`: it reuses every stored result and "
    "adds the nine Tamaas runs (under a minute on two cores with the default meshes, seconds "
    "with `--quick`).")
