; MetaWorld pick-place-v3: reach the puck, grasp it, lift it off the table, carry it to the goal
; (which may be in the air).
(define (domain metaworld-pick-place)
  (:requirements :strips :typing :negative-preconditions)
  (:types hand puck)
  (:predicates
    (hand-at ?h - hand ?p - puck)             ; fingertips at the puck
    (holding ?h - hand ?p - puck)             ; fingers closed on the puck
    (lifted ?p - puck)                        ; puck off the table
    (at-goal ?p - puck))                      ; puck within the success radius of the goal
  (:action reach
    :parameters (?h - hand ?p - puck)
    :precondition (not (hand-at ?h ?p))
    :effect (hand-at ?h ?p))
  (:action grasp
    :parameters (?h - hand ?p - puck)
    :precondition (and (hand-at ?h ?p) (not (holding ?h ?p)))
    :effect (holding ?h ?p))
  (:action lift
    :parameters (?h - hand ?p - puck)
    :precondition (and (holding ?h ?p) (not (lifted ?p)))
    :effect (lifted ?p))
  (:action carry
    :parameters (?h - hand ?p - puck)
    :precondition (and (holding ?h ?p) (lifted ?p) (not (at-goal ?p)))
    :effect (at-goal ?p)))
