"""An example submission: the README's walk-through ranks this potential with the smoke profile.

    tox -e bench -- --profile smoke --potential tests.submission.example:ProgressAndDistance

φ = scale · (max_idx / n − distance to the next subgoal's place): plan progress, with the
distance to go as a tie-breaker inside each plan step. It reads only the shaping context (the
progress and the task's locate/positions hooks), so it is a function of the augmented state and
keeps the optimal policy.
"""

from __future__ import annotations

import numpy as np

from planshape.shaping.potentials import Potential, ShapingContext


class ProgressAndDistance(Potential):
    """Plan progress plus the negated distance from the end effector to the next subgoal.

    Example:
        >>> from planshape.shaping.potentials import ShapingContext
        >>> context = ShapingContext(obs=None, progress=1, t=0, subgoals=(frozenset(),) * 3)
        >>> ProgressAndDistance()(context)
        0.5
    """

    def potential(self, ctx: ShapingContext) -> float:
        done = ctx.progress / ctx.final if ctx.final else 0.0
        if ctx.geometry is None or ctx.progress == ctx.final:
            return done
        targets = ctx.geometry.locate(ctx.subgoals[ctx.next_index])
        positions = ctx.geometry.positions(ctx.obs)
        entity = next(iter(targets))
        return done - float(np.linalg.norm(np.asarray(positions[entity]) - targets[entity]))
