; The end effector moves between places in the plane. Places are regions of the workspace
; (waypoints or grid cells); neighbors says which straight moves are free of walls.
(define (domain maze-reach)
  (:requirements :strips :typing :negative-preconditions :equality)
  (:types place)
  (:predicates
    (robot_at ?c - place)
    (neighbors ?a ?b - place))
  (:action move
    :parameters (?from ?to - place)
    :precondition (and (robot_at ?from) (neighbors ?from ?to) (not (= ?from ?to)))
    :effect (and (robot_at ?to) (not (robot_at ?from)))))
