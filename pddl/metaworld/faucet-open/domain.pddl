; MetaWorld faucet-open-v3: put the gripper against the faucet's handle, swing it open.
(define (domain metaworld-faucet-open)
  (:requirements :strips :typing :negative-preconditions)
  (:types hand handle faucet)
  (:predicates
    (handle-of ?k - handle ?f - faucet)       ; static
    (hand-at ?h - hand ?k - handle)           ; gripper at the handle's end
    (open ?f - faucet))                       ; handle swung round to the goal
  (:action reach-handle
    :parameters (?h - hand ?k - handle)
    :precondition (not (hand-at ?h ?k))
    :effect (hand-at ?h ?k))
  (:action turn-open
    :parameters (?h - hand ?k - handle ?f - faucet)
    :precondition (and (hand-at ?h ?k) (handle-of ?k ?f) (not (open ?f)))
    :effect (open ?f)))
