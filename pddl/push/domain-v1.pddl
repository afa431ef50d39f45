; The push domain of the v1 tasks' grid-diagonal model: the paper's object is a cylinder, which
; a move of the end effector past it may touch. A diagonal move from ?from to ?to passes the two
; cells beside both (?side1, ?side2); it is free only when the object is in neither, as in ?to.
; Everything else is the v0 domain (domain.pddl): moves between neighbours, pushes in line.
(define (domain push)
  (:requirements :strips :typing :negative-preconditions :equality)
  (:types place box)
  (:predicates
    (robot_at ?p - place)
    (object_at ?b - box ?p - place)
    (neighbors ?a ?b - place)
    (diagonal ?from ?to ?side1 ?side2 - place)
    (push_line ?behind ?from ?to ?behind-after - place))
  (:action move
    :parameters (?from ?to - place ?b - box)
    :precondition (and (robot_at ?from) (neighbors ?from ?to) (not (= ?from ?to))
                       (not (object_at ?b ?to)))
    :effect (and (robot_at ?to) (not (robot_at ?from))))
  (:action move_diagonal
    :parameters (?from ?to ?side1 ?side2 - place ?b - box)
    :precondition (and (robot_at ?from) (diagonal ?from ?to ?side1 ?side2)
                       (not (object_at ?b ?to)) (not (object_at ?b ?side1))
                       (not (object_at ?b ?side2)))
    :effect (and (robot_at ?to) (not (robot_at ?from))))
  (:action push
    :parameters (?behind ?from ?to ?behind-after - place ?b - box)
    :precondition (and (robot_at ?behind) (object_at ?b ?from)
                       (push_line ?behind ?from ?to ?behind-after) (not (object_at ?b ?to)))
    :effect (and (not (robot_at ?behind)) (robot_at ?behind-after)
                 (not (object_at ?b ?from)) (object_at ?b ?to))))
