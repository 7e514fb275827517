"""Finite-element numerics that know no scene: elasticity, contact search,
surface geometry."""
