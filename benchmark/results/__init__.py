"""Results: stored runs read as data, scored, and rendered as the leaderboard.

* :mod:`~planshape.results.frame` — :func:`load`: every stored evaluation row as one tidy
  pandas DataFrame (``planshape export``);
* :mod:`~planshape.results.scoring` — aggregation: IQM, bootstrap intervals, normalized
  scores, the cells of the leaderboard;
* :mod:`~planshape.results.leaderboard` — ``planshape leaderboard``: Markdown, HTML, JSON;
* :mod:`~planshape.results.figures` — the leaderboard's plots;
* :mod:`~planshape.results.videos` — ``planshape render``: a run's policy as an animation.

Example:
    >>> from planshape import results
    >>> results.load is results.frame.load
    True
"""

from planshape.results import frame
from planshape.results.frame import export, load

__all__ = ["export", "frame", "load"]
