"""Hertzian contact of elastic bodies: contact ellipse, pressure, approach.

Conventions used throughout:

* Elliptic integrals K(m), E(m) take the parameter m = k**2 (as scipy.special).
* ``e_star`` is E* with 1/E* = (1 - nu1**2)/E1 + (1 - nu2**2)/E2 (not E' = 2 E*).
* Principal radii: positive for a convex surface, negative for a concave one,
  ``inf`` for a flat one.  SI units throughout (m, N, Pa, rad).
"""

from ._contact import Body, Contact, LineContact, contact, line_contact
from ._ellipse import ellipticity
from ._load_path import LoadPath, LoadPathSpring, load_path
from ._tangential import (
    FrettingLoop,
    Tangential,
    TangentialSpring,
    dundurs_beta,
    proportional_loading,
    tangential_compliance,
    tangential_history,
)

__all__ = ["Body", "Contact", "FrettingLoop", "LineContact", "LoadPath", "LoadPathSpring",
           "Tangential", "TangentialSpring", "contact", "dundurs_beta", "ellipticity",
           "line_contact", "load_path", "proportional_loading", "tangential_compliance",
           "tangential_history"]
__version__ = "0.1.0"
