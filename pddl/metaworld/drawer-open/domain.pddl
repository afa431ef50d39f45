; MetaWorld drawer-open-v3: get the gripper to the drawer's handle, then pull the drawer open.
(define (domain metaworld-drawer-open)
  (:requirements :strips :typing :negative-preconditions)
  (:types hand handle drawer)
  (:predicates
    (handle-of ?k - handle ?d - drawer)       ; static
    (hand-at ?h - hand ?k - handle)           ; gripper at the handle
    (open ?d - drawer))                       ; handle pulled out to the goal
  (:action reach-handle
    :parameters (?h - hand ?k - handle)
    :precondition (not (hand-at ?h ?k))
    :effect (hand-at ?h ?k))
  (:action pull-open
    :parameters (?h - hand ?k - handle ?d - drawer)
    :precondition (and (hand-at ?h ?k) (handle-of ?k ?d) (not (open ?d)))
    :effect (open ?d)))
