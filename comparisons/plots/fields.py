"""The fields of both roads at the report's field points: σ(x) and v(x), BEM markers on
semi-analytic lines, and their difference at the BEM's collocation points.

Units: x/λ, σ(1 − ν²)/E0 (positive in compression), v/h (positive into the body)
(`docs/conventions.md`).
"""
from __future__ import annotations

from . import kept_when_unchanged, pyplot, save


def plot_fields(fig, rows):
    """One column per field point: fields on top (σ left axis, v/h right), differences below.

    Parameters
    ----------
    fig : matplotlib Figure
    rows : list of dict
        `comparisons.report_numbers.field_comparison`'s rows.

    Returns
    -------
    fig
    """
    axes = fig.subplots(2, len(rows), sharex=True)
    for j, row in enumerate(rows):
        top, bot = axes[0, j], axes[1, j]
        top.plot(row["x"], row["pressure"], "k-", lw=1.0, label="semi-analytic σ")
        twin = top.twinx()
        twin.plot(row["x"], row["displacement"], "C0-", lw=1.0)
        twin.set_ylabel("v/h", color="C0", fontsize=8)
        bem, norms = row["bem"], row["norms"]
        if bem:
            step = max(1, len(bem["x"]) // 64)
            top.plot(bem["x"][::step], bem["pressure"][::step], "o", ms=3, mfc="none",
                     color="C3", label="BEM σ")
            twin.plot(bem["x"][::step], bem["displacement"][::step], "s", ms=2.5, mfc="none",
                      color="C0")
            bot.plot(bem["x"], bem["pressure_difference"], "C3-", lw=0.8, label="Δσ")
            bot.plot(bem["x"], bem["displacement_difference"], "C0-", lw=0.8, label="Δv/h")
            bot.set_title(f"L∞: σ {norms['pressure_Linf']:.1e}·max σ, "
                          f"v {norms['displacement_Linf']:.1e}·h", fontsize=8)
        top.set_title(f"{row['label']}\np̃∞ = {row['load']:g}, V/V0 = {row['speed']:g}",
                      fontsize=9)
        top.set_ylabel("σ(1 − ν²)/E0", fontsize=8)
        bot.set_xlabel("x/λ")
        bot.set_ylabel("BEM − semi-analytic", fontsize=8)
        top.legend(fontsize=7, loc="upper left")
        bot.legend(fontsize=7)
        for a_ in (top, bot):
            a_.grid(True, alpha=0.3)
    return fig


@kept_when_unchanged
def write_figure(path_png, rows):
    """`plot_fields` on a figure 4.2 in wide per field point, written to ``path_png``."""
    fig = pyplot().figure(figsize=(4.2 * len(rows), 6.0))
    plot_fields(fig, rows)
    return save(fig, path_png)
