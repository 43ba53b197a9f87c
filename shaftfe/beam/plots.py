"""Figures of the beam model (matplotlib imported inside, Agg backend)."""

from __future__ import annotations


def plot_results(results, fmt: str = "png") -> bytes:
    """Deflection line and nominal von Mises stress for each rpm, as image bytes."""
    import io

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for r in results:
        ax1.plot(r.x, r.u * 1e3, label=f"{r.rpm:g} rpm")
        ax2.plot(r.x_sec, r.sigma_vm, label=f"{r.rpm:g} rpm")
        for n in r.notches:
            ax2.plot([n.x_mm], [n.sigma_peak_MPa], "v", color="k", ms=4)
        labels: dict[float, list[str]] = {}
        for k, s in r.stations.items():
            labels.setdefault(s.x_mm, []).append(k)
        for xs, names in labels.items():
            s = r.stations[names[0]]
            ax1.annotate(" / ".join(names), (xs, s.u_mm * 1e3), fontsize=7)
    ax1.set_ylabel("|deflection| µm")
    ax2.set_ylabel("nominal von Mises MPa\n(▼ Kt × nominal)")
    ax2.set_xlabel("x mm")
    ax1.legend()
    ax1.set_title(f"{results[0].name}: Timoshenko beam "
                  f"({'rigid supports' if results[0].rigid_supports else 'bearing springs'})")
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format=fmt, dpi=120)
    plt.close(fig)
    return buf.getvalue()
