"""Charts with matplotlib, headless."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def figure(rows=1, cols=1, title=None, size=(6.5, 4.5)):
    """A figure of rows x cols panels, each `size` inches; returns (fig, flat list of axes)."""
    fig, axes = plt.subplots(rows, cols, figsize=(size[0] * cols, size[1] * rows), squeeze=False)
    if title:
        fig.suptitle(title)
    for ax in axes.flat:
        ax.grid(True, alpha=0.4)
    return fig, list(axes.flat)


def save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
