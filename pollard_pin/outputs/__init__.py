"""Paint's outputs read back, a layer above the figures and below the commands: paint.json's
schema (:mod:`.schema`: the one writer of its text, the one reader) and a paint output folder
(:mod:`.folder`: its files, its report, its film, a cell's robots; :mod:`.overlay`: the
viewer's drawing of it)."""
