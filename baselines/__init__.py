"""Reference leaderboard entries: the potentials every submission is ranked against.

One flat list of registrations; nothing is imported until a potential is made.
"""

from planshape.shaping.potentials import register_potential

# ---- the source paper (Section 4.1) ---------------------------------------------------------
register_potential("plan-based", "planshape.baselines.paper:PlanBased")
register_potential("time-varying", "planshape.baselines.paper:TimeVarying")
register_potential("distance-varying", "planshape.baselines.paper:DistanceVarying")

# ---- planner heuristics and plan distance (solve maze-reach; see heuristic.py, plan_distance.py)
register_potential("plan-distance", "planshape.baselines.plan_distance:PlanDistance")
register_potential(
    "plan-distance-sum", "planshape.baselines.plan_distance:PlanDistance", measure="sum"
)
register_potential("h-add", "planshape.baselines.heuristic:HeuristicPotential", heuristic="h-add")
register_potential("h-ff", "planshape.baselines.heuristic:HeuristicPotential", heuristic="h-ff")
register_potential("h-star", "planshape.baselines.heuristic:HeuristicPotential", heuristic="h-star")
register_potential(
    "h-add-discounted",
    "planshape.baselines.heuristic:HeuristicPotential",
    heuristic="h-add",
    gamma="learner",
)
register_potential(
    "h-ff-discounted",
    "planshape.baselines.heuristic:HeuristicPotential",
    heuristic="h-ff",
    gamma="learner",
)
register_potential(
    "h-star-discounted",
    "planshape.baselines.heuristic:HeuristicPotential",
    heuristic="h-star",
    gamma="learner",
)
register_potential("h-star-geodesic", "planshape.baselines.heuristic:HStarGeodesic")

# ---- control: the hand-crafted dense reward's distance as a potential (see goal_distance.py)
register_potential("goal-distance", "planshape.baselines.goal_distance:GoalDistance")
register_potential("plan-path", "planshape.baselines.plan_path:PlanPath")
