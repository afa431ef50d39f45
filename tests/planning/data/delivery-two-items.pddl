; Two items: the robot must come back between them (one item at a time): 10 steps.
(define (problem deliver-two)
  (:domain delivery)
  (:objects kitchen lab - room
            cup book - item)
  (:init (at depot)
         (item-at cup kitchen) (item-at book lab)
         (connected depot kitchen) (connected kitchen depot)
         (connected kitchen lab) (connected lab kitchen))
  (:goal (and (delivered cup) (delivered book))))
