; The lab is not connected to anything: the book cannot be reached.
(define (problem deliver-unreachable)
  (:domain delivery)
  (:objects kitchen lab - room
            book - item)
  (:init (at depot)
         (item-at book lab)
         (connected depot kitchen) (connected kitchen depot))
  (:goal (delivered book)))
