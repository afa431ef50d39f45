; One intermediate subgoal: the top-left corner outside the walls.
(define (problem maze-reach-single)
  (:domain maze-reach)
  (:objects start via goal - place)
  (:init (robot_at start)
         (neighbors start via) (neighbors via goal))
  (:goal (robot_at goal)))
