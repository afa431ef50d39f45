(define (domain delivery)
  (:requirements :strips :typing)
  (:types place)
  (:predicates (at ?p - place)
  (:action go
    :parameters (?from ?to - place)
    :precondition (at ?from)
    :effect (and (at ?to) (not (at ?from)))))
