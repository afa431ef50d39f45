; The end effector reaches the box, then pushes it through two waypoints to the goal.
(define (problem push-multi)
  (:domain push)
  (:objects start behind_box box_start w1 behind_w1 w2 behind_w2 goal behind_goal - place
            box - box)
  (:init (robot_at start) (object_at box box_start)
         (neighbors start behind_box)
         (push_line behind_box box_start w1 behind_w1)
         (push_line behind_w1 w1 w2 behind_w2)
         (push_line behind_w2 w2 goal behind_goal))
  (:goal (object_at box goal)))
