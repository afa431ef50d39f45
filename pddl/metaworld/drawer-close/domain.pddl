; MetaWorld drawer-close-v3: the drawer starts open; get the gripper to its front, push it shut.
; "closed" is a positive predicate on purpose: a subgoal counts as reached when its fluent atoms
; hold, so every stage of a plan must make some atom true.
(define (domain metaworld-drawer-close)
  (:requirements :strips :typing :negative-preconditions)
  (:types hand handle drawer)
  (:predicates
    (handle-of ?k - handle ?d - drawer)       ; static
    (hand-at ?h - hand ?k - handle)           ; gripper at the drawer's front
    (closed ?d - drawer))                     ; drawer pushed back to the goal
  (:action reach-handle
    :parameters (?h - hand ?k - handle)
    :precondition (not (hand-at ?h ?k))
    :effect (hand-at ?h ?k))
  (:action push-closed
    :parameters (?h - hand ?k - handle ?d - drawer)
    :precondition (and (hand-at ?h ?k) (handle-of ?k ?d) (not (closed ?d)))
    :effect (closed ?d)))
