; MetaWorld window-open-v3: get the gripper to the window's handle, slide the window open.
(define (domain metaworld-window-open)
  (:requirements :strips :typing :negative-preconditions)
  (:types hand handle window)
  (:predicates
    (handle-of ?k - handle ?w - window)       ; static
    (hand-at ?h - hand ?k - handle)           ; gripper at the handle's push point
    (open ?w - window))                       ; handle slid to the goal
  (:action reach-handle
    :parameters (?h - hand ?k - handle)
    :precondition (not (hand-at ?h ?k))
    :effect (hand-at ?h ?k))
  (:action slide-open
    :parameters (?h - hand ?k - handle ?w - window)
    :precondition (and (hand-at ?h ?k) (handle-of ?k ?w) (not (open ?w)))
    :effect (open ?w)))
