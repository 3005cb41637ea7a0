"""One colour and marker per formulation, the same in every figure of every report: a fixed map
over the registry's formulations (`contactbench list`, in its order; tests/python/test_styles.py
checks the list against the driver). A distributed variant `dist-X` takes X's colour and marker,
hollow. Every formulation's (colour, marker, fill) is distinct, so 11 or 18 series never share
a style as they did on a 10-colour cycle."""

# The registry's formulations, in the order `contactbench list` prints them.
FORMULATIONS = ["implicit-fb", "nonsmooth-fb", "active-set", "ipopt-energy", "ipopt-mpcc",
                "nlopt-merit", "nlopt-energy", "nlopt-mpcc", "siconos-lemke",
                "siconos-newton-fb", "siconos-newton-min", "petsc-rsls", "petsc-ssls",
                "dist-implicit-fb", "dist-nonsmooth-fb", "dist-active-set", "dist-petsc-rsls",
                "dist-petsc-ssls"]

_BASE = [f for f in FORMULATIONS if not f.startswith("dist-")]
_COLOURS = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown",
            "tab:pink", "tab:gray", "tab:olive", "tab:cyan", "black", "gold", "navy"]
_MARKERS = ["o", "s", "^", "v", "D", "P", "X", "*", "h", "<", ">", "p", "d"]
UNKNOWN = dict(color="0.6", marker=".", markerfacecolor="0.6")


def style(formulation):
    """matplotlib keywords (color, marker, markerfacecolor) of `formulation`."""
    distributed = formulation.startswith("dist-")
    base = formulation[len("dist-"):] if distributed else formulation
    if base not in _BASE:
        return dict(UNKNOWN)
    k = _BASE.index(base)
    return dict(color=_COLOURS[k], marker=_MARKERS[k],
                markerfacecolor="none" if distributed else _COLOURS[k])


def colour(formulation):
    return style(formulation)["color"]


def colours(formulations):
    """{formulation: colour} for a list of formulations (what comparison._colours returned)."""
    return {f: colour(f) for f in formulations}
