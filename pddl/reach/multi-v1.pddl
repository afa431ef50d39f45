; The source paper's multi-subgoal model (v1 tasks): three subgoals in order, each of which holds
; at either of two points on the two ways around the obstacle, then the goal.
(define (problem reach-multi-v1)
  (:domain reach)
  (:objects start subgoal1 subgoal2 subgoal3 goal - place)
  (:init (robot_at start)
         (neighbors start subgoal1) (neighbors subgoal1 subgoal2) (neighbors subgoal2 subgoal3)
         (neighbors subgoal3 goal))
  (:goal (robot_at goal)))
