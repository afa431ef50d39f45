; The source paper's single-subgoal model (v1 tasks): one subgoal, "subgoal", which holds at
; either of two points on the way around the obstacle (reach: either end of the wall; maze-reach:
; above either side wall), then the goal.
(define (problem reach-single-v1)
  (:domain reach)
  (:objects start subgoal goal - place)
  (:init (robot_at start)
         (neighbors start subgoal) (neighbors subgoal goal))
  (:goal (robot_at goal)))
