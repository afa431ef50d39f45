; MetaWorld reach-v3: move the gripper's fingertips to the goal position.
(define (domain metaworld-reach)
  (:requirements :strips :typing :negative-preconditions)
  (:types hand location)
  (:predicates
    (hand-at ?h - hand ?l - location))        ; fingertips within 5 cm of the location
  (:action move-hand
    :parameters (?h - hand ?l - location)
    :precondition (not (hand-at ?h ?l))
    :effect (hand-at ?h ?l)))
