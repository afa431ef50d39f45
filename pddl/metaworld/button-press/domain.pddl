; MetaWorld button-press-v3: line the gripper up in front of the button, push it in.
(define (domain metaworld-button-press)
  (:requirements :strips :typing :negative-preconditions)
  (:types hand button)
  (:predicates
    (hand-in-front ?h - hand ?b - button)     ; gripper lined up with the button, in front of it
    (pressed ?b - button))                    ; button pushed in to the goal depth
  (:action line-up
    :parameters (?h - hand ?b - button)
    :precondition (not (hand-in-front ?h ?b))
    :effect (hand-in-front ?h ?b))
  (:action press
    :parameters (?h - hand ?b - button)
    :precondition (and (hand-in-front ?h ?b) (not (pressed ?b)))
    :effect (pressed ?b)))
