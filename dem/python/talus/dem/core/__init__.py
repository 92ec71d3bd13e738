"""The scene and what it holds, as Yade scripts reach them: ``O``, bodies, materials, contacts, forces, the periodic cell, clumps."""
