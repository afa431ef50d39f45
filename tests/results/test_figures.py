"""Figure titles stay inside the saved image, however narrow the figure."""

from __future__ import annotations

import io

import pytest

from planshape.results.figures import suptitle

LONG_TITLES = (
    "planshape/MetaWorld-button-press-topdown-v3: success rate during training\n(mean over "
    "seeds, 95% bootstrap CI; sparse black, dense grey)",
    "planshape/MazeReachRandomized-v1: final distance to the goal\n(lower is better; bars: "
    "mean over seeds with 95% bootstrap CI; points: each seed)",
    "Probability of improvement, pooled over tasks (95% stratified bootstrap CIs)",
)


@pytest.mark.parametrize("width", [3.7, 4.0, 5.2, 6.8, 10.0])
@pytest.mark.parametrize("title", LONG_TITLES)
def test_a_wrapped_title_fits_the_figure_width(width: float, title: str) -> None:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width, 3.0), layout="constrained")
    fig.subplots(1, 2)
    text = suptitle(fig, title)
    fig.savefig(io.BytesIO(), format="png", dpi=110)  # lays the figure out
    extent = text.get_window_extent()
    assert extent.x0 >= 0 and extent.x1 <= fig.bbox.width, (extent, fig.bbox)
    assert extent.y1 <= fig.bbox.height


def test_the_title_keeps_its_words_and_its_own_line_breaks() -> None:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(4.0, 3.0))
    suptitle(fig, LONG_TITLES[0])
    wrapped = fig.get_suptitle()
    assert "".join(wrapped.split()) == "".join(LONG_TITLES[0].split())  # nothing lost
    assert wrapped.splitlines()[0] == "planshape/MetaWorld-button-press-"  # at a hyphen
    assert any(line.startswith("(mean over") for line in wrapped.splitlines())
