"""Reference leaderboard entries: the potentials every submission is ranked against.

One flat list of registrations; nothing is imported until a potential is made.
"""

from planshape.potentials import register_potential

# ---- the source paper (Section 4.1) ---------------------------------------------------------
register_potential("plan-based", "planshape.baselines.paper:PlanBased")
register_potential("time-varying", "planshape.baselines.paper:TimeVarying")
register_potential("distance-varying", "planshape.baselines.paper:DistanceVarying")
