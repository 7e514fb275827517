"""Hertzian contact of elastic bodies: contact ellipse, pressure, approach.

Conventions used throughout:

* Elliptic integrals K(m), E(m) take the parameter m = k**2 (as scipy.special).
* ``e_star`` is E* with 1/E* = (1 - nu1**2)/E1 + (1 - nu2**2)/E2 (not E' = 2 E*).
* Principal radii: positive for a convex surface, negative for a concave one,
  ``inf`` for a flat one.  SI units throughout (m, N, Pa, rad).
* Hertz's theory holds for contacts much smaller than the bodies' radii:
  :func:`contact` and :func:`line_contact` issue a :class:`HertzValidityWarning`
  beyond a/R = ``A_OVER_R_LIMIT``.
"""

import dataclasses as _dataclasses
import inspect as _inspect

from ._build_info import show_config
from ._contact import (
    A_OVER_R_LIMIT,
    Body,
    Contact,
    HertzValidityWarning,
    LineContact,
    contact,
    line_contact,
)
from ._ellipse import ellipticity
from ._impact import (
    DAMPING_LAWS,
    DampedImpact,
    Impact,
    ImpactHistory,
    damped_impact,
    damping_coefficient,
    impact,
    restitution,
)
from ._load_path import LoadPath, LoadPathSpring, load_path
from ._oblique import ObliqueHistory, ObliqueImpact, oblique_impact
from ._stress import LineSubsurface, Subsurface
from ._tangential import (
    FrettingLoop,
    Tangential,
    TangentialSpring,
    dundurs_beta,
    proportional_loading,
    tangential_compliance,
    tangential_history,
)

# Every type a public function or method returns is public: Contact.subsurface gives a
# Subsurface, LineContact.subsurface a LineSubsurface, Tangential.maxima a SlidingMaxima.
__all__ = ["A_OVER_R_LIMIT", "Body", "Contact", "DAMPING_LAWS", "DampedImpact", "FrettingLoop",
           "HertzValidityWarning", "Impact", "ImpactHistory", "LineContact", "LineSubsurface",
           "LoadPath", "LoadPathSpring", "ObliqueHistory", "ObliqueImpact", "SlidingMaxima",
           "Subsurface", "Tangential", "TangentialSpring", "contact", "damped_impact",
           "damping_coefficient", "dundurs_beta", "ellipticity", "impact", "line_contact",
           "load_path", "oblique_impact", "proportional_loading", "restitution", "show_config",
           "tangential_compliance", "tangential_history"]
__version__ = "0.1.0"
#: Public names imported when first used: hertz._friction needs scipy, which ``import
#: hertz`` does not load.
_LAZY = {"SlidingMaxima": "._friction"}


def __getattr__(name: str):
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(_LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'hertz' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY))


def _public_signature(cls) -> _inspect.Signature:
    """The signature of a result class without its private fields (``_geometry``, ``_nu``,
    ...): hertz makes these objects and fills those; they are no part of the public face
    (``help()``, the API reference)."""
    sig = _inspect.signature(cls)
    return sig.replace(parameters=[p for p in sig.parameters.values()
                                   if not p.name.startswith("_")],
                       return_annotation=_inspect.Signature.empty)


for _name in sorted(set(__all__) - set(_LAZY)):
    _cls = globals()[_name]
    if (_inspect.isclass(_cls) and _dataclasses.is_dataclass(_cls)
            and any(p.startswith("_") for p in _inspect.signature(_cls).parameters)):
        _cls.__signature__ = _public_signature(_cls)
del _name, _cls
