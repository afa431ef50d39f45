; Three waypoints around the walls: left of the start, above the left wall, above the opening.
(define (problem maze-reach-multi)
  (:domain maze-reach)
  (:objects start w1 w2 w3 goal - place)
  (:init (robot_at start)
         (neighbors start w1) (neighbors w1 w2) (neighbors w2 w3) (neighbors w3 goal))
  (:goal (robot_at goal)))
