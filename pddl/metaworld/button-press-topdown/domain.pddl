; MetaWorld button-press-topdown-v3: bring the gripper over the button, press it down.
(define (domain metaworld-button-press-topdown)
  (:requirements :strips :typing :negative-preconditions)
  (:types hand button)
  (:predicates
    (hand-above ?h - hand ?b - button)        ; gripper over the button (and not below it)
    (pressed ?b - button))                    ; button pushed down to the goal depth
  (:action move-above
    :parameters (?h - hand ?b - button)
    :precondition (not (hand-above ?h ?b))
    :effect (hand-above ?h ?b))
  (:action press
    :parameters (?h - hand ?b - button)
    :precondition (and (hand-above ?h ?b) (not (pressed ?b)))
    :effect (pressed ?b)))
