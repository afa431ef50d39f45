; MetaWorld push-v3: bring the gripper to the puck, then push (or drag) it to the goal.
(define (domain metaworld-push)
  (:requirements :strips :typing :negative-preconditions)
  (:types hand puck)
  (:predicates
    (hand-at ?h - hand ?p - puck)             ; fingertips at the puck
    (at-goal ?p - puck))                      ; puck within the success radius of the goal
  (:action reach
    :parameters (?h - hand ?p - puck)
    :precondition (not (hand-at ?h ?p))
    :effect (hand-at ?h ?p))
  (:action push
    :parameters (?h - hand ?p - puck)
    :precondition (and (hand-at ?h ?p) (not (at-goal ?p)))
    :effect (at-goal ?p)))
