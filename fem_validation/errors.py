"""The one exception fem_validation raises for its own failures."""


class FEMValidationError(RuntimeError):
    """Meshing failed, the active set did not settle, or a linear solve did not converge.

    The message carries the state at the failure (iteration, sizes, residuals).
    """
