"""Our runs end to end: block validation, curved bodies, friction, the
refinement study."""
