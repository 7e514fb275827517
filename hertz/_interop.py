"""Arrays of other libraries at hertz's boundary: dask, pandas, xarray, pint.

hertz computes on float64 numpy arrays, and lazily, block by block, on dask
arrays.  The other libraries' objects are unwrapped at the public entry
points into numpy (or dask) values plus a :class:`Recipe` that wraps the
results the same way:

* pandas: a Series (or DataFrame) gives Series (DataFrames) on the same
  index (and columns), named after the result field.  Every pandas input of
  one call must have the same index: hertz does not align (an outer join
  would invent NaN rows that are then refused, an inner join would drop
  rows silently); it raises and says how to align.  A numpy array or scalar
  beside them must broadcast to the Series' shape (by position, as in
  pandas arithmetic).
* xarray: DataArrays broadcast by dimension name, as in xarray arithmetic;
  their coordinates on shared dimensions must be equal (no alignment, as
  for pandas).  Results are DataArrays on the broadcast dimensions and
  coordinates; dask-backed DataArrays stay lazy.
* pint: Quantities are converted to SI (radii and lengths to m, moduli,
  pressures and stresses to Pa, loads to N, angles to rad, Poisson's ratio
  to a plain number); a quantity of the wrong dimension is a TypeError
  naming the parameter and the unit it needs.  Plain numbers beside them
  are taken as SI.  Results are Quantities in SI units of the registry of
  the first Quantity given.
* dask: arrays of different chunks, and numpy arrays beside dask arrays,
  are brought to common chunks; errors raised when a block is computed name
  the parameter, the value and the index in the whole array.

No library is imported here at import time: a value is recognised by the
module of its type, and its library imported only when one arrives.

This module knows no result type and imports no other module of hertz but
``_validate``: it sits below the solvers.  Each result type takes itself apart
and rebuilds itself (``_UNITS``, ``_rebuild`` on Contact and LineContact; the
dataclass fields of Tangential and FrettingLoop), and each solver wraps its own
results with :func:`unwrap` and :meth:`Recipe.wrap` (``hertz._contact``,
``hertz._ellipse``, ``hertz._tangential``).
"""

from __future__ import annotations

import functools
import math
import re

import numpy as np

from ._validate import as_float_array, with_index

#: libraries whose objects are unwrapped and the results wrapped again
_WRAPPERS = frozenset(("pandas", "xarray", "pint"))

# the units of parameters and results: SI unit (pint spelling) and what it measures
M, PA, N, RAD, ONE, N_PER_M, PER_M = "m", "Pa", "N", "rad", "", "N/m", "1/m"
_MEASURES = {M: "a length", PA: "a pressure (or modulus)", N: "a force", RAD: "an angle",
             ONE: "a dimensionless number", N_PER_M: "a force per length",
             PER_M: "a curvature"}
#: axes of a stress tensor in an xarray result
_TENSOR_DIMS = ("row", "column")


def library(value) -> str:
    """The top-level package of ``value``'s type (``'pandas'``, ``'dask'``, ``'builtins'``...)."""
    return type(value).__module__.partition(".")[0]


def is_dask(value) -> bool:
    """Whether ``value`` is a dask array (computed block by block, lazily)."""
    return type(value).__module__.startswith("dask.")


def any_wrapped(*values) -> bool:
    """Whether any value is a pandas, xarray or pint object (cheap for floats and ndarrays)."""
    for value in values:
        kind = type(value)
        if (kind is not float and kind is not np.ndarray
                and kind.__module__.partition(".")[0] in _WRAPPERS):
            return True
    return False


def any_foreign(*values) -> bool:
    """Whether any value is wrapped (pandas, xarray, pint) or a dask array."""
    for value in values:
        kind = type(value)
        if kind is not float and kind is not np.ndarray and (
                kind.__module__.partition(".")[0] in _WRAPPERS
                or kind.__module__.startswith("dask.")):
            return True
    return False


# --------------------------------------------------------------------------- unwrap / wrap

class Recipe:
    """How to wrap results like the inputs: container (pandas/xarray) and units (pint)."""

    __slots__ = ("kind", "template", "registry")

    def __init__(self, kind=None, template=None, registry=None):
        #: None, "series", "frame" or "xarray"; template: the Series/DataFrame, or
        #: (dims, coords) of the broadcast DataArrays
        self.kind, self.template, self.registry = kind, template, registry

    def wrap(self, value, unit: str, name: str | None = None, tensor: bool = False):
        """``value`` (numpy, dask or float, of the broadcast shape, plus (3, 3) for a
        ``tensor``) as the inputs were: Series, DataArray, Quantity in ``unit``."""
        kind = self.kind
        if kind == "series" and not tensor:
            import pandas as pd

            value = pd.Series(value, index=self.template.index, name=name, copy=False)
        elif kind == "frame" and not tensor:
            import pandas as pd

            value = pd.DataFrame(value, index=self.template.index,
                                 columns=self.template.columns, copy=False)
        elif kind == "xarray":
            import xarray as xr

            dims, coords = self.template
            if tensor:
                dims = dims + _TENSOR_DIMS
                coords = dict(coords)
                coords.update({d: list("xyz") for d in _TENSOR_DIMS})
            value = xr.DataArray(value, coords=coords, dims=dims, name=name)
        if self.registry is not None and unit is not None:  # a flag stays a plain bool
            value = self.registry.Quantity(value, _unit(self.registry, unit))
        return value

    def wrap_points(self, value, unit: str, name: str, axis: str = "point"):
        """``value`` of shape (n, broadcast shape): a leading axis of n points in front
        of the inputs' shape, wrapped as the inputs were.  pandas Series: a DataFrame with a
        row per point (index named ``axis``) and a column per element of the Series;
        DataFrames: numpy (pandas has no third axis); xarray: a DataArray with the
        dimension ``axis`` in front; pint: a Quantity in ``unit``."""
        kind = self.kind
        if kind == "series":
            import pandas as pd

            value = pd.DataFrame(value, index=pd.RangeIndex(len(value), name=axis),
                                 columns=self.template.index, copy=False)
        elif kind == "xarray":
            import xarray as xr

            dims, coords = self.template
            value = xr.DataArray(value, coords=coords, dims=(axis,) + tuple(dims), name=name)
        if self.registry is not None:
            value = self.registry.Quantity(value, _unit(self.registry, unit))
        return value

    def labelled(self, exc: ValueError) -> ValueError:
        """``exc`` with the pandas labels or xarray coordinates of the index it names."""
        found = _AT_INDEX.search(str(exc))
        if self.kind is None or found is None:
            return exc
        position = tuple(int(i) for i in re.findall(r"\d+", found.group(1)))
        if self.kind == "xarray":
            dims, coords = self.template
            if len(position) != len(dims):
                return exc
            parts = [f"{d}={_item(coords[d].values[i]) if d in coords else i!r}"
                     for d, i in zip(dims, position, strict=True)]
            label = "(" + ", ".join(parts) + ")"
        elif self.kind == "series" and len(position) == 1:
            label = _item(self.template.index[position[0]])
            if label == position[0]:  # a default RangeIndex: nothing to add
                return exc
            label = f"(label {label!r})"
        elif self.kind == "frame" and len(position) == 2:
            row, column = position
            label = (f"(row {_item(self.template.index[row])!r}, "
                     f"column {_item(self.template.columns[column])!r})")
        else:
            return exc
        text = str(exc)
        return ValueError(f"{text[:found.end()]} {label}{text[found.end():]}")


#: where a message names the index of the bad element (see _validate.index_text)
_AT_INDEX = re.compile(r"at index (\d+|\((?:\d+, )*\d+,?\))")


def _item(value):
    """A numpy scalar label as the Python value it stands for."""
    return value.item() if hasattr(value, "item") else value


@functools.lru_cache(maxsize=64)
def _unit(registry, unit: str):
    """The registry's Unit for ``unit`` (parsing the text costs more than the rest)."""
    return registry.Unit(unit or "dimensionless")


def _to_si(quantity, name: str, unit: str):
    """The magnitude of a pint Quantity in the SI ``unit``."""
    from pint import DimensionalityError, OffsetUnitCalculusError

    try:
        return quantity.to(_unit(quantity._REGISTRY, unit)).magnitude
    except (DimensionalityError, OffsetUnitCalculusError):
        raise TypeError(f"{name} must be {_MEASURES[unit]} (a quantity convertible to "
                        f"{unit or 'a plain number'}), got a quantity in {quantity.units}"
                        ) from None


def unwrap(items):
    """Plain values (numpy, dask, float) of ``(name, value, unit)`` items and the
    :class:`Recipe` to wrap results like them."""
    names = [name for name, _, _ in items]
    plain, registry = [], None
    for name, value, unit in items:
        if library(value) == "pint":
            if not hasattr(value, "magnitude") or not hasattr(value, "to"):
                raise TypeError(f"{name} must be a number or a pint Quantity, got "
                                f"{type(value).__name__} {value!r}")
            if registry is None:
                registry = value._REGISTRY
            value = _to_si(value, name, unit)
        plain.append(value)
    libraries = {library(v) for v in plain} & _WRAPPERS
    recipe = Recipe(registry=registry)
    if "pint" in libraries or (registry is not None and libraries):
        raise TypeError("pint Quantities inside or beside pandas/xarray objects are not "
                        "supported: give the Series/DataArray values in SI units (m, Pa, N, "
                        "rad), e.g. series.pint.to('m').pint.magnitude")
    if libraries == {"pandas", "xarray"}:
        raise TypeError("give pandas or xarray inputs, not both in one call (convert with "
                        "DataArray.to_series() or xarray.DataArray(series))")
    if "pandas" in libraries:
        plain = _unwrap_pandas(names, plain, recipe)
    elif "xarray" in libraries:
        plain = _unwrap_xarray(names, plain, recipe)
    for name, value in zip(names, plain, strict=True):
        if library(value) in _WRAPPERS:  # e.g. a DataArray of Quantities (pint-xarray)
            raise TypeError(f"{name}: a {type(value).__name__} inside a pandas or xarray "
                            "object is not supported; give plain numbers in SI units")
    return plain, recipe


def _pandas_values(value, name: str):
    import pandas as pd

    if not isinstance(value, (pd.Series, pd.DataFrame)):
        raise TypeError(f"{name} must be a number, an array, a pandas Series or DataFrame, "
                        f"got a pandas {type(value).__name__}")
    dtypes = [value.dtype] if isinstance(value, pd.Series) else list(value.dtypes)
    if all(pd.api.types.is_numeric_dtype(d) and not pd.api.types.is_bool_dtype(d)
           and not pd.api.types.is_complex_dtype(d) for d in dtypes):
        # nullable dtypes: a missing value becomes NaN, which is then refused with its index
        return value.to_numpy(dtype=np.float64, na_value=np.nan)
    return value.to_numpy()  # refused by the numeric check, which names the dtype


def _unwrap_pandas(names, values, recipe):
    import pandas as pd

    first = None
    out = []
    for name, value in zip(names, values, strict=True):
        if library(value) != "pandas":
            out.append(value)
            continue
        if first is None:
            first = (name, value)
        else:
            first_name, template = first
            if isinstance(value, pd.DataFrame) != isinstance(template, pd.DataFrame):
                raise TypeError(f"{first_name} and {name}: give all pandas inputs as Series "
                                "(DataFrame columns) or all as DataFrames of the same shape")
            if not value.index.equals(template.index) or (
                    isinstance(value, pd.DataFrame)
                    and not value.columns.equals(template.columns)):
                raise ValueError(
                    f"the index of {name} differs from that of {first_name}: hertz does not "
                    "align pandas inputs; align them first, e.g. "
                    "x, y = x.align(y, join='inner')")
        out.append(_pandas_values(value, name))
    first_name, template = first
    recipe.kind = "frame" if isinstance(template, pd.DataFrame) else "series"
    recipe.template = template
    for name, value in zip(names, out, strict=True):
        if is_dask(value):
            raise TypeError(f"{name} is a dask array beside the pandas input {first_name}: "
                            "compute it first (or use dask-backed xarray DataArrays)")
        _require_fits(name, np.shape(value), template.shape, f"the pandas input {first_name}")
    return out


def _require_fits(name, shape, template_shape, what):
    """A plain array beside labelled inputs must broadcast to their shape."""
    try:
        fits = np.broadcast_shapes(shape, template_shape) == template_shape
    except ValueError:
        fits = False
    if not fits:
        raise ValueError(f"{name} of shape {shape} does not broadcast to the shape "
                         f"{template_shape} of {what}")


def _unwrap_xarray(names, values, recipe):
    import xarray as xr

    arrays = {}
    for name, value in zip(names, values, strict=True):
        if library(value) == "xarray":
            if not isinstance(value, xr.DataArray):
                raise TypeError(f"{name} must be a number, an array or an xarray DataArray, "
                                f"got an xarray {type(value).__name__}")
            arrays[name] = value
    template = next(iter(arrays.values()))
    if len(arrays) > 1:
        try:
            xr.align(*arrays.values(), join="exact", copy=False)
        except ValueError:
            raise ValueError(
                f"the coordinates of {', '.join(arrays)} differ on a shared dimension: hertz "
                "does not align DataArrays; align them first (xarray.align(..., join='inner'))"
            ) from None
        template = xr.broadcast(*arrays.values())[0]
    dims = template.dims
    recipe.kind = "xarray"
    recipe.template = (dims, {k: v for k, v in template.coords.items()})
    out = []
    for name, value in zip(names, values, strict=True):
        if name in arrays:
            own = [d for d in dims if d in value.dims]
            data = value.transpose(*own).data
            # size-1 axes for the dimensions it lacks: broadcast by name, not position
            value = data[tuple(slice(None) if d in value.dims else None for d in dims)]
        else:
            _require_fits(name, np.shape(value), template.shape,
                          f"the DataArrays (dims {dims})")
        out.append(value)
    return out


def _wrap_like(value, plain):
    """A Body field ``plain`` (checked, SI) wrapped like the user's ``value``."""
    kind = library(value)
    if kind == "pandas":
        import pandas as pd

        if isinstance(value, pd.Series):
            return pd.Series(plain, index=value.index, name=value.name, copy=False)
        return pd.DataFrame(plain, index=value.index, columns=value.columns, copy=False)
    if kind == "xarray":
        import xarray as xr

        return xr.DataArray(plain, coords=value.coords, dims=value.dims, name=value.name)
    return plain


def init_fields(obj, given, units, stand_in) -> None:
    """Set the fields ``given`` ({name: value}) of the frozen ``obj`` from pandas, xarray
    or pint values: each is checked as ``type(obj)(**plain values)`` checks it, and kept
    in the form given (a Quantity in the SI unit of ``units``).  A check that fails is
    repeated for each field alone beside the valid ``stand_in`` values, so that the error
    carries that field's labels."""
    cls = type(obj)
    plain, recipes = {}, {}
    for name, value in given.items():
        values, recipes[name] = unwrap([(name, value, units[name])])
        plain[name] = values[0]
    try:
        checked = cls(**plain)
    except ValueError as exc:
        # which field: check each alone beside valid stand-ins, for its labels
        for name in given:
            try:
                cls(**{**stand_in, name: plain[name]})
            except ValueError as alone:
                raise recipes[name].labelled(alone) from None
        raise exc from None  # pragma: no cover - some field fails alone
    setter = object.__setattr__
    for name, value in given.items():
        field = getattr(checked, name)
        if library(value) == "pint":
            field = value._REGISTRY.Quantity(field, _unit(value._REGISTRY, units[name]))
        elif library(value) in _WRAPPERS:
            field = _wrap_like(value, field)
        setter(obj, name, field)


# --------------------------------------------------------------------------- methods

def call_method(result, method: str, arguments, unit, *options, rtype=None, check=None,
                tensor: bool = False):
    """``result.method(*arguments, *options)`` of a result whose fields or arguments are
    pandas, xarray, pint or dask: unwrap, compute (block by block for dask), wrap.

    The result type says how it is taken apart and rebuilt: ``type(result)._UNITS``
    ({field: unit}) are the fields its plain twin is made of, ``result._nu`` the Poisson's
    ratios (nu1, nu2), then the Young's moduli (E1, E2) where it keeps them, and
    ``type(result)._rebuild(fields, nu)`` makes the twin of plain values, on which the
    method runs as for numpy input.  ``arguments`` are (name, value, unit); ``unit`` is that
    of the method's value (a str; ``tensor``: a (..., 3, 3) stress tensor), or with
    ``rtype`` (the type of the method's value, rebuilt from its fields in order) the
    dict {field: unit} of that type (unit None: a flag, kept a plain bool).  ``check()``
    judges the ``options`` before any block is computed."""
    kind = type(result)
    own = kind._UNITS
    # Poisson's ratios, then the Young's moduli where the result keeps them (tangential)
    moduli = [("nu1", ONE), ("nu2", ONE), ("E1", PA), ("E2", PA)][:len(result._nu)]
    items = ([(k, getattr(result, k), u) for k, u in own.items()]
             + [(k, v, u) for (k, u), v in zip(moduli, result._nu, strict=True)]
             + list(arguments))
    plain, recipe = unwrap(items)
    nown = len(own) + len(moduli)
    if check is not None:
        check()
    plain[nown:] = [v if is_dask(v) else as_float_array(v, name)
                    for v, (name, _, _) in zip(plain[nown:], arguments, strict=True)]

    def evaluate(*values):
        # a result of plain values (whole arrays, or a dask block of each), every field
        # included, on which the method runs as for numpy input
        twin = kind._rebuild(values[:len(own)], values[len(own):nown])
        return getattr(kind, method)(twin, *values[nown:], *options)

    if any(is_dask(v) for v in plain):
        if rtype is not None:
            names = list(unit)
            fields = dask_map(lambda *v: _as_tuple(evaluate(*v), names), plain, nout=len(names))
            out = rtype(*(f if unit[k] is not None else f.astype(bool)
                          for f, k in zip(fields, names, strict=True)))
        else:
            out = dask_map(evaluate, plain, trailing=(3, 3) if tensor else ())
    else:
        try:
            out = evaluate(*plain)
        except ValueError as exc:
            raise recipe.labelled(exc) from None
    if rtype is not None:
        return rtype(*(recipe.wrap(getattr(out, k), u, k) for k, u in unit.items()))
    return recipe.wrap(out, unit, method, tensor=tensor)


def call_result_method(result, method: str, arguments, unit: str, units):
    """``result.method(*arguments)`` of a dataclass result (a Tangential, a FrettingLoop)
    whose fields (of ``units``) or arguments are pandas, xarray or pint: unwrap, compute on
    the plain twin ``type(result)(**fields)``, wrap in ``unit``."""
    import dataclasses

    names = [k for k, u in units.items() if u is not None]
    items = [(k, getattr(result, k), units[k]) for k in names] + list(arguments)
    plain, recipe = unwrap(items)
    twin = dict(zip(names, plain, strict=False))
    twin = type(result)(**{f.name: twin.get(f.name, getattr(result, f.name))
                           for f in dataclasses.fields(result)})
    values = [as_float_array(v, name)
              for v, (name, _, _) in zip(plain[len(names):], arguments, strict=True)]
    try:
        out = getattr(type(result), method)(twin, *values)
    except ValueError as exc:
        raise recipe.labelled(exc) from None
    return recipe.wrap(out, unit, method)


def _as_tuple(out, names):
    return tuple(getattr(out, k) for k in names)


# --------------------------------------------------------------------------- dask

def dask_map(func, args, nout=None, trailing=(), names=None):
    """``func`` over the blocks of ``args`` (dask arrays, numpy arrays, floats), lazily.

    The arguments broadcast together; numpy arrays are made single-chunk dask
    arrays and all are rechunked to the common refinement of their chunks.
    ``func(*blocks)`` returns an array of the blocks' broadcast shape (plus
    ``trailing``), or a tuple of ``nout`` of them (then a tuple of dask arrays
    is returned).  ``names`` name the arguments in the error for a dask array
    that is not of real numbers.  A ValueError in a block is raised again for the first bad
    element of that block, with its index in the whole broadcast array.
    """
    import dask.array as da

    shape = np.broadcast_shapes(*(np.shape(a) for a in args))
    ndim = len(shape)
    loop = tuple(f"i{k}" for k in range(ndim))
    pairs = []
    for k, a in enumerate(args):
        if is_dask(a) and a.dtype.kind not in "iuf":
            name = names[k] if names else "the input"
            raise TypeError(f"{name} must be a real number or an array of them, got a dask "
                            f"array of dtype {a.dtype}")
        if is_dask(a) or (isinstance(a, np.ndarray) and a.ndim):
            a = a if is_dask(a) else da.from_array(a, chunks=-1)
            pairs += [a.astype(np.float64, copy=False), loop[ndim - a.ndim:]]
        else:
            pairs += [float(a), None]
    chunks, arrays = da.core.unify_chunks(*pairs, warn=False)
    # each block gets the global indices of its rows along every axis: the offsets
    # that turn an index within the block into one within the whole array
    offsets = []
    for k, index in enumerate(loop):
        offsets += [da.arange(shape[k], chunks=(chunks.get(index, (shape[k],)),)), (index,)]
    stacked = nout is not None
    extra = tuple(f"t{k}" for k in range(len(trailing)))
    out_index = (("out",) if stacked else ()) + loop + extra
    new_axes = dict(zip(extra, trailing, strict=True))
    if stacked:
        new_axes["out"] = nout

    def block(*blocks):
        rows, values = blocks[:ndim], blocks[ndim:]
        bshape = tuple(len(r) for r in rows)
        out = np.empty((nout,) + bshape + tuple(trailing)) if stacked else None
        try:
            if stacked and type(func) is np.ufunc:  # the kernel writes the stack in place
                func(*values, out=tuple(out[k, ...] for k in range(nout)))
                return out
            result = func(*values)
        except ValueError as exc:
            raise _located(func, values, [int(r[0]) if len(r) else 0 for r in rows], shape,
                           exc) from None
        if not stacked:
            return np.broadcast_to(result, bshape + tuple(trailing)).astype(np.float64)
        for k, r in enumerate(result):
            out[k] = r
        return out

    # the offsets first: blockwise takes each axis' chunks from the first array that has it
    pairs = offsets + [x for pair in zip(arrays, pairs[1::2], strict=True) for x in pair]
    result = da.blockwise(block, out_index, *pairs, new_axes=new_axes, dtype=np.float64,
                          meta=np.empty((0,) * len(out_index)), align_arrays=False,
                          concatenate=True)
    return tuple(result[k] for k in range(nout)) if stacked else result


def _located(func, values, starts, shape, exc) -> ValueError:
    """The error of the first bad element (C order) of a block, found by bisection
    (each element's check is independent), with its index in the whole array."""
    bshape = np.broadcast_shapes(*(np.shape(v) for v in values))
    flat = [np.broadcast_to(v, bshape).reshape(-1) if np.ndim(v) else v for v in values]

    def error(part):
        try:
            func(*(v[part] if np.ndim(v) else v for v in flat))
        except ValueError as found:
            return found
        return None

    lo, hi = 0, math.prod(bshape)
    while hi - lo > 1:  # a bad element lies in [lo, hi)
        mid = (lo + hi) // 2
        if error(slice(lo, mid)) is not None:
            hi = mid
        else:
            lo = mid
    one = error(lo) if bshape else exc
    if one is None:  # pragma: no cover - an error that no single element reproduces
        return exc
    local = np.unravel_index(lo, bshape) if bshape else ()
    index = tuple(s + int(i) for s, i in zip(starts, local, strict=True))
    return with_index(one, shape, int(np.ravel_multi_index(index, shape)) if shape else 0)
