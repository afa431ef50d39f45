; gymnasium-robotics FetchReach: move the gripper to the goal position.
(define (domain fetch-reach)
  (:requirements :strips :typing :negative-preconditions)
  (:types gripper location)
  (:predicates
    (gripper-at ?g - gripper ?l - location))  ; within the env's 5 cm success radius
  (:action move-gripper
    :parameters (?g - gripper ?l - location)
    :precondition (not (gripper-at ?g ?l))
    :effect (gripper-at ?g ?l)))
