"""What a team takes to the range: the flight card (:mod:`.card`), Google Earth
maps (:mod:`.kml`) and file exports (:mod:`.exports`).  Numeric-only."""
