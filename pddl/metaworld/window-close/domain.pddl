; MetaWorld window-close-v3: the window starts open; get the gripper to its handle, slide it shut.
(define (domain metaworld-window-close)
  (:requirements :strips :typing :negative-preconditions)
  (:types hand handle window)
  (:predicates
    (handle-of ?k - handle ?w - window)       ; static
    (hand-at ?h - hand ?k - handle)           ; gripper at the handle's push point
    (closed ?w - window))                     ; handle slid back to the goal
  (:action reach-handle
    :parameters (?h - hand ?k - handle)
    :precondition (not (hand-at ?h ?k))
    :effect (hand-at ?h ?k))
  (:action slide-closed
    :parameters (?h - hand ?k - handle ?w - window)
    :precondition (and (hand-at ?h ?k) (handle-of ?k ?w) (not (closed ?w)))
    :effect (closed ?w)))
