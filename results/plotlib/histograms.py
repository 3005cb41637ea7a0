"""The axes of an iteration histogram, shared by the report's and the comparison's figures:
bins labelled by their ranges and readable however many there are, and a count axis that
turns logarithmic when the small bins would vanish beside the large ones."""
import numpy as np

# Beyond this ratio of the largest to the smallest nonzero count, a linear axis draws the
# smallest bins a pixel high or less (a figure some 300 pixels tall).
LOG_RATIO = 30.0
# Up to this many bins the labels fit side by side; beyond it they are turned.
UPRIGHT_BINS = 8


def label_bins(ax, positions, labels):
    """One tick per bin at `positions`, labelled by its range ("3-4"); turned 45 degrees, right
    end at the tick, when there are many so that neighbours do not overlap."""
    many = len(labels) > UPRIGHT_BINS
    ax.set_xticks(positions)
    ax.set_xticklabels(labels, rotation=45 if many else 0, ha="right" if many else "center",
                       rotation_mode="anchor", fontsize=8 if many else 10)


def wants_log(counts):
    """True when the nonzero counts span more than LOG_RATIO (the small bins would vanish)."""
    c = np.asarray(counts, dtype=float).ravel()
    c = c[c > 0]
    return c.size > 1 and c.max() / c.min() > LOG_RATIO


def count_axis(ax, what, log):
    """The count axis, labelled `what`: logarithmic when `log` (said so in the label), with
    its floor under one so that a bin of one step shows."""
    if log:
        ax.set_yscale("log")
        ax.set_ylim(bottom=0.7)
        ax.set_ylabel(f"{what} (log scale)")
    else:
        ax.set_ylabel(what)
