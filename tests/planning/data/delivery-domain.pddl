; Delivery: a robot carries items, one at a time, to the depot.
; Exercises typing (with a subtype hierarchy), a constant, negative preconditions and equality.
(define (domain delivery)
  (:requirements :strips :typing :negative-preconditions :equality)
  (:types room hall - place
          item)
  (:constants depot - hall)
  (:predicates
    (at ?p - place)
    (item-at ?i - item ?p - place)
    (carrying ?i - item)
    (hands-full)
    (delivered ?i - item)
    (connected ?a ?b - place))
  (:action go
    :parameters (?from ?to - place)
    :precondition (and (at ?from) (connected ?from ?to) (not (= ?from ?to)))
    :effect (and (at ?to) (not (at ?from))))
  (:action pick
    :parameters (?i - item ?p - place)
    :precondition (and (at ?p) (item-at ?i ?p) (not (hands-full)))
    :effect (and (carrying ?i) (hands-full) (not (item-at ?i ?p))))
  (:action unload
    :parameters (?i - item ?p - place)
    :precondition (and (at ?p) (carrying ?i) (= ?p depot))
    :effect (and (delivered ?i) (not (carrying ?i)) (not (hands-full)))))
