"""Conversion and checking of user input, done once at the public boundary.

Internal code receives clean float64 arrays and never re-checks them.
"""

from __future__ import annotations

import math
import numbers

import numpy as np


def as_float_array(value, name: str) -> np.ndarray:
    """Convert ``value`` to a float64 ndarray, or raise TypeError naming it.

    Integers and floats of any width are accepted (a Python int beyond the
    double range is a ValueError naming it); booleans, complex numbers,
    strings, objects and masked arrays (whose mask would be lost) are not.
    """
    if isinstance(value, np.ma.MaskedArray):
        raise TypeError(
            f"{name} is a numpy masked array, and hertz does not apply masks: pass "
            f"{name}.filled(value) (masked elements replaced) or {name}.compressed() (the "
            "unmasked elements only)")
    try:
        arr = np.asarray(value)
    except Exception as exc:  # ragged nested sequences and the like
        raise TypeError(f"{name} must be a real number or an array of them: {exc}") from None
    if arr.dtype.kind == "O":  # Python ints beyond 64 bits, mixed with floats or not
        return _from_python_numbers(value, arr, name)
    if arr.dtype.kind not in "iuf":
        raise TypeError(
            f"{name} must be a real number or an array of them, got {_describe(value, arr)}"
        )
    if arr.dtype.kind == "f" and arr.dtype.itemsize > 8:  # long double: check the range
        with np.errstate(over="ignore", under="ignore"):
            out = arr.astype(np.float64)
        lost = (np.isfinite(arr) & ~np.isfinite(out)) | ((arr != 0) & (out == 0))
        if lost.any():
            i = first_failure(~lost)
            raise ValueError(f"{name} must be within the range of a double (magnitude "
                             "at most 1.7976931348623157e308, and 0 or at least 5e-324), got "
                             f"{arr.reshape(-1)[i]!r}{index_text(arr.shape, i)}")
        return out
    return arr.astype(np.float64, copy=False)


def int_to_float(value: int, name: str) -> float:
    """A Python int as a float; beyond the double range a ValueError naming it."""
    try:
        return float(value)
    except OverflowError:
        raise ValueError(f"{name} must be within the range of a double (magnitude at most "
                         f"1.7976931348623157e308), got the int {_int_text(value)}") from None


def _from_python_numbers(value, arr: np.ndarray, name: str) -> np.ndarray:
    """An object array of Python (or numpy) ints and floats as float64."""
    out = np.empty(arr.shape)
    flat = out.reshape(-1)
    for i, v in enumerate(arr.reshape(-1)):
        if type(v) is bool or isinstance(v, np.bool_) or not isinstance(v, numbers.Real):
            raise TypeError(
                f"{name} must be a real number or an array of them, got {_describe(value, arr)}")
        try:
            flat[i] = v
        except OverflowError:
            shown = f"the int {_int_text(v)}" if isinstance(v, int) else f"a {type(v).__name__}"
            raise ValueError(f"{name} must be within the range of a double (magnitude at most "
                             f"1.7976931348623157e308), got {shown}"
                             f"{index_text(arr.shape, i)}") from None
    return out


def _int_text(value: int) -> str:
    """A huge int in scientific notation (str() of it may be refused beyond 4300 digits)."""
    shift = max(abs(value).bit_length() - 64, 0)
    exponent = math.log10(abs(value) >> shift) + shift * math.log10(2.0)
    power = math.floor(exponent)
    mantissa = f"{10 ** (exponent - power):.3f}"
    if mantissa == "10.000":
        mantissa, power = "1.000", power + 1
    return f"{'-' if value < 0 else ''}{mantissa}e+{power}"


def index_text(shape: tuple[int, ...], flat_index: int) -> str:
    """`` at index i`` (or a tuple for N-d shapes) for element ``flat_index``; '' for 0-d."""
    if not shape:
        return ""
    index = np.unravel_index(flat_index, shape)
    index = int(index[0]) if len(index) == 1 else tuple(int(i) for i in index)
    return f" at index {index}"


def error_at(name: str, arr: np.ndarray, flat_index: int, allowed: str) -> ValueError:
    """The ValueError for element ``flat_index`` (C order) of ``arr``."""
    value = arr.reshape(-1)[flat_index].item()
    return ValueError(f"{name} must be {allowed}, got {value!r}{index_text(arr.shape, flat_index)}")


def require(name: str, arr: np.ndarray, ok: np.ndarray, allowed: str) -> None:
    """Raise ValueError at the first element where ``ok`` is false.

    ``ok`` must be false for NaN (write comparisons so that it is).
    """
    ok = np.broadcast_to(ok, arr.shape)
    if not ok.all():
        raise error_at(name, arr, int(np.argmin(ok.reshape(-1))), allowed)


def first_failure(ok: np.ndarray) -> int:
    """Flat index (C order) of the first element where ``ok`` is false."""
    return int(np.argmin(np.asarray(ok).reshape(-1)))


def with_index(exc: ValueError, shape: tuple[int, ...], flat_index: int) -> ValueError:
    """``exc``'s message for element ``flat_index`` of an array of ``shape``, with its index:
    after the offending value (``..., got -1.0 at index 3``) or in front of a sentence."""
    where = index_text(shape, flat_index)
    if not where or ", got " in str(exc):
        return ValueError(f"{exc}{where}")
    return ValueError(f"{where.strip()}: {exc}")


def is_duck_array(value) -> bool:
    """Whether ``value`` is a dask array: such input is passed on unconverted and
    computed lazily.  (pandas, xarray and pint objects are unwrapped by
    ``hertz._interop``; other array types are converted with numpy.asarray.)"""
    return not isinstance(value, _PLAIN) and type(value).__module__.startswith("dask.")


#: types that are never dask arrays, ruled out first (their module name costs more to read)
_PLAIN = (float, int, np.ndarray, np.generic)


def broadcast_shape(**arrays) -> tuple[int, ...]:
    """The common shape of named arrays; the error names the parameters and shapes."""
    try:
        return np.broadcast_shapes(*(np.shape(v) for v in arrays.values()))
    except ValueError:
        shapes = ", ".join(f"{k} {np.shape(v)}" for k, v in arrays.items())
        raise ValueError(f"shapes do not broadcast together: {shapes}") from None


def _describe(value, arr: np.ndarray) -> str:
    if arr.ndim == 0:
        return f"{type(value).__name__} {value!r}"
    return f"an array of dtype {arr.dtype}"
