; One item in the kitchen: the optimal plan has 4 steps.
(define (problem deliver-cup)
  (:domain delivery)
  (:objects Kitchen lab - room
            cup - item)
  (:init (at DEPOT)
         (item-at cup kitchen)
         (connected depot kitchen) (connected kitchen depot)
         (connected kitchen lab) (connected lab kitchen))
  (:goal (and (delivered cup))))
