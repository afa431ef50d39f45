; MetaWorld plate-slide-v3: get the gripper behind the plate, slide it into the goal.
(define (domain metaworld-plate-slide)
  (:requirements :strips :typing :negative-preconditions)
  (:types hand plate)
  (:predicates
    (hand-at ?h - hand ?p - plate)            ; gripper behind the plate
    (at-goal ?p - plate))                     ; plate within the success radius of the goal
  (:action reach
    :parameters (?h - hand ?p - plate)
    :precondition (not (hand-at ?h ?p))
    :effect (hand-at ?h ?p))
  (:action slide
    :parameters (?h - hand ?p - plate)
    :precondition (and (hand-at ?h ?p) (not (at-goal ?p)))
    :effect (at-goal ?p)))
