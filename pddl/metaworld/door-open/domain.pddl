; MetaWorld door-open-v3: hook the door's handle, then swing the door open.
(define (domain metaworld-door-open)
  (:requirements :strips :typing :negative-preconditions)
  (:types hand handle door)
  (:predicates
    (handle-of ?k - handle ?d - door)         ; static
    (hand-at ?h - hand ?k - handle)           ; gripper at the handle
    (open ?d - door))                         ; handle swung to the goal
  (:action reach-handle
    :parameters (?h - hand ?k - handle)
    :precondition (not (hand-at ?h ?k))
    :effect (hand-at ?h ?k))
  (:action pull-open
    :parameters (?h - hand ?k - handle ?d - door)
    :precondition (and (hand-at ?h ?k) (handle-of ?k ?d) (not (open ?d)))
    :effect (open ?d)))
