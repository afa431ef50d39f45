"""Results: stored runs read as data, scored, and rendered as the leaderboard.

By job, around the typed row (:class:`~planshape.results.rows.StoredRow`):

* :mod:`~planshape.results.rows` — the row schema, defined once; reading and checking run files;
* :mod:`~planshape.results.frame` — :func:`load`: every stored row as one tidy pandas DataFrame
  (``planshape export``);
* :mod:`~planshape.results.stats` — statistics, pure functions on arrays: IQM, stratified
  bootstrap intervals, probability of improvement, normalized scores, curve areas;
* :mod:`~planshape.results.cells` — runs grouped into cells (task, algorithm, entry) and scored:
  :func:`~planshape.results.cells.summarize`, :func:`~planshape.results.cells.aggregate`;
* :mod:`~planshape.results.provenance` — how the results were produced, and the caveats;
* :mod:`~planshape.results.tables` — the leaderboard's tables as data (numbers become text here);
* :mod:`~planshape.results.verdict` — what each (task, algorithm) cell can decide (budget check);
* :mod:`~planshape.results.outcome` — what it decided: whether a planning-derived potential
  reaches dense (shaping outcome);
* :mod:`~planshape.results.page` — one page model of the leaderboard;
* :mod:`~planshape.results.render` — that page as Markdown and, through jinja2 templates, HTML;
* :mod:`~planshape.results.figures`, :mod:`~planshape.results.plots` — the plots;
* :mod:`~planshape.results.leaderboard` — :func:`~planshape.results.leaderboard.render_leaderboard`:
  ``LEADERBOARD.md``, ``index.html``, ``summary.json`` and the plots of a results folder;
* :mod:`~planshape.results.evidence` — ``planshape evidence``: every rendered profile's verdicts
  on one page (``leaderboard/EVIDENCE.md``);
* :mod:`~planshape.results.videos` — ``planshape render``: a run's policy as an animation.

Example:
    >>> from planshape import results
    >>> results.load is results.frame.load
    True
"""

from planshape.results import frame
from planshape.results.frame import export, load

__all__ = ["export", "frame", "load"]
