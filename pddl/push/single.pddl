; One intermediate subgoal: the end effector behind the box; then one push to the goal.
(define (problem push-single)
  (:domain push)
  (:objects start behind_box box_start goal behind_goal - place
            box - box)
  (:init (robot_at start) (object_at box box_start)
         (neighbors start behind_box)
         (push_line behind_box box_start goal behind_goal))
  (:goal (object_at box goal)))
