; The end effector reaches the box, then pushes it. A push moves the box from ?from to ?to and
; leaves the end effector at ?behind-after, in contact behind the box's new place; which places
; line up for a push is static (push_line), as is which moves of the end effector are free.
(define (domain push)
  (:requirements :strips :typing :negative-preconditions :equality)
  (:types place box)
  (:predicates
    (robot_at ?p - place)
    (object_at ?b - box ?p - place)
    (neighbors ?a ?b - place)
    (push_line ?behind ?from ?to ?behind-after - place))
  (:action move
    :parameters (?from ?to - place ?b - box)
    :precondition (and (robot_at ?from) (neighbors ?from ?to) (not (= ?from ?to))
                       (not (object_at ?b ?to)))
    :effect (and (robot_at ?to) (not (robot_at ?from))))
  (:action push
    :parameters (?behind ?from ?to ?behind-after - place ?b - box)
    :precondition (and (robot_at ?behind) (object_at ?b ?from)
                       (push_line ?behind ?from ?to ?behind-after) (not (object_at ?b ?to)))
    :effect (and (not (robot_at ?behind)) (robot_at ?behind-after)
                 (not (object_at ?b ?from)) (object_at ?b ?to))))
