; MetaWorld handle-press-v3: put the gripper on the end of the lever, press the lever down.
(define (domain metaworld-handle-press)
  (:requirements :strips :typing :negative-preconditions)
  (:types hand handle)
  (:predicates
    (hand-at ?h - hand ?k - handle)           ; gripper on the lever's end
    (pressed ?k - handle))                    ; lever's end pressed down to the goal height
  (:action reach-handle
    :parameters (?h - hand ?k - handle)
    :precondition (not (hand-at ?h ?k))
    :effect (hand-at ?h ?k))
  (:action press
    :parameters (?h - hand ?k - handle)
    :precondition (and (hand-at ?h ?k) (not (pressed ?k)))
    :effect (pressed ?k)))
