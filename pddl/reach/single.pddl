; One intermediate subgoal halfway between the start and the goal.
(define (problem reach-single)
  (:domain reach)
  (:objects start via goal - place)
  (:init (robot_at start)
         (neighbors start via) (neighbors via goal))
  (:goal (robot_at goal)))
