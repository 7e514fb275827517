"""Our own sources: block meshes and their contact solve, true curved
bodies, Coulomb friction; each gives its result as a ``results`` type."""
