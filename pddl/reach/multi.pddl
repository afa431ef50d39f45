; Three waypoints evenly spaced on the straight line from the start to the goal.
(define (problem reach-multi)
  (:domain reach)
  (:objects start w1 w2 w3 goal - place)
  (:init (robot_at start)
         (neighbors start w1) (neighbors w1 w2) (neighbors w2 w3) (neighbors w3 goal))
  (:goal (robot_at goal)))
