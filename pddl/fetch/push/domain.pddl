; gymnasium-robotics FetchPush: bring the (blocked) gripper to the block, push it to the goal.
(define (domain fetch-push)
  (:requirements :strips :typing :negative-preconditions)
  (:types gripper block)
  (:predicates
    (touching ?g - gripper ?b - block)        ; gripper at the block
    (at-goal ?b - block))                     ; block within the env's 5 cm success radius
  (:action reach
    :parameters (?g - gripper ?b - block)
    :precondition (not (touching ?g ?b))
    :effect (touching ?g ?b))
  (:action push
    :parameters (?g - gripper ?b - block)
    :precondition (and (touching ?g ?b) (not (at-goal ?b)))
    :effect (at-goal ?b)))
