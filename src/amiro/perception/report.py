"""Human-readable output of the perception evaluation: tables beside the paper's, a plot."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from amiro.core.config import ConfigError

ESTIMATORS = (("paper_formula", "paper formula"), ("improved", "improved"))


def _axes(errors: dict[str, dict[str, float]], metric: str) -> str:
    values = errors.get(metric, {})
    return " ".join(f"{values.get(a, float('nan')):5.2f}" for a in "xyz")


def print_report(report: dict[str, Any]) -> None:
    print(
        f"{report['samples']} samples, {report['localised']} localised ({report['wall_time_s']} s)"
    )
    print(
        "MAE x y z (m): paper's table | paper formula here (hfov/vfov at the image edge) | "
        "improved here"
    )
    rows = [("overall", report["paper_table"], report["paper_formula"], report["improved"])]
    for group in ("by_distance", "by_posture", "by_camera"):
        for name, g in report[group].items():
            rows.append(
                (f"{group[3:]} {name}", g["paper_table"], g["paper_formula"], g["improved"])
            )
    for label, table, formula, better in rows:
        print(
            f"  {label:<26} {_axes(table, 'mae')} | {_axes(formula, 'mae')} | "
            f"{_axes(better, 'mae')}"
        )
    full = report["paper_formula_full_fov"]
    print(f"  {'overall, full-field reading':<26} {'':17} | {_axes(full, 'mae')} |")
    c = report["counting_mae"]
    print(f"counting MAE: here (paper); {c['what']}")
    print(
        f"  overall {c['overall']:.2f} ({c['paper']['overall']:.2f}), excluding lying "
        f"{c['excluding_lying']:.2f} ({c['paper']['excluding_lying']:.2f})"
    )
    for name, v in c["by_posture"].items():
        print(f"  {name:<16} {v:.2f} ({c['paper']['by_posture'][name]:.2f})")
    for d, v in c["by_distance"].items():
        p = c["paper"]["by_distance"].get(d, {"all": float("nan"), "excluding_lying": float("nan")})
        print(
            f"  {d} m: {v['all']:.2f} ({p['all']:.2f}), excluding lying "
            f"{v['excluding_lying']:.2f} ({p['excluding_lying']:.2f})"
        )
    print(f"improved estimator: {report['improved_ms_per_detection']} ms per detection")
    if "plot" in report:
        print(f"plot: {report['plot']}")


def plot_by_distance(report: dict[str, Any], path: Path) -> Path:
    """MAE per axis by distance, both estimators and the paper's Table 8, as a PNG."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    groups = report["by_distance"]
    distances = [float(d) for d in groups]
    fig, axes = plt.subplots(1, 3, figsize=(11, 3.4), sharey=True)
    for ax, axis in zip(axes, "xyz", strict=True):
        for key, label, style in (
            ("paper_table", "paper (Table 8)", "k--"),
            ("paper_formula", "paper formula (edge angles), here", "C1-o"),
            ("improved", "improved, here", "C0-o"),
        ):
            ax.plot(
                distances, [g[key]["mae"].get(axis) for g in groups.values()], style, label=label
            )
        ax.set_title(f"MAE {axis}")
        ax.set_xlabel("distance to the person (m)")
    axes[0].set_ylabel("m")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    try:
        fig.savefig(path, dpi=100)
    except OSError as exc:
        raise ConfigError(f"{path}: cannot write the plot: {exc}") from None
    finally:
        plt.close(fig)
    return path
