"""Hostile and everyday-odd input to the CSV and meshio readers (issue 22, items 5, 7, 9).

Files are built here as people build them: by hand, as Excel writes them (a byte-order
mark, CRLF, semicolons and decimal commas, quoted headers with units, rows padded with
empty cells), and through meshio with broken cells.  The reference values are the numbers
written into the files, converted by hand; every malformed file must give one ValueError
naming the file (and the line where there is one), never another exception.
"""

from __future__ import annotations

import random
import tracemalloc

import numpy as np
import pytest

meshio = pytest.importorskip("meshio", reason="needs the fem extra (meshio)")
pytest.importorskip("scipy")

from fem_validation.readers import csv_file as table_module  # noqa: E402
from fem_validation.readers import read_result  # noqa: E402
from fem_validation.readers.csv_file import read_force_approach  # noqa: E402
from fem_validation.readers.tangential_csv import read_history, read_tangential  # noqa: E402
from fem_validation.results.contact import ContactFrame, ContactResult, ResultError  # noqa: E402
from fem_validation.results.tangential import TangentialResult  # noqa: E402

#: A quarter of a Hertz contact of radius A [m] with peak P0 [Pa] on a 9 x 9 grid: the
#: pressure p0 sqrt(1 - r^2/a^2) written out here, not taken from the package.
A, P0 = 2e-4, 1.2e9
_G = np.linspace(0.0, 1.5 * A, 9)
X, Y = (v.ravel() for v in np.meshgrid(_G, _G))
P = P0 * np.sqrt(np.clip(1 - (X**2 + Y**2) / A**2, 0.0, None))
FORCE_MM = 25.0  # the quarter model's own force [N]


def _rows(sep=",", length=1e3, pressure=1e-6, decimal="."):
    out = []
    for x, y, p in zip(X, Y, P, strict=True):
        cells = [f"{v:.12g}".replace(".", decimal) for v in (x * length, y * length,
                                                              p * pressure)]
        out.append(sep.join(cells))
    return out


def _write(path, lines, newline="\n", bom=False):
    path.write_bytes((b"\xef\xbb\xbf" if bom else b"")
                     + (newline.join(lines) + newline).encode())
    return path


def _plain(path):
    return _write(path, [f"# force = {FORCE_MM}", "# units = mm", "x,y,p", *_rows()])


def _check_quarter(res):
    """The result holds the numbers written, in SI, as a quarter of 4 x 25 N."""
    assert res.symmetry == "quarter" and res.force == pytest.approx(4 * FORCE_MM, rel=1e-15)
    np.testing.assert_allclose(res.points[:, 0], X, rtol=1e-10, atol=1e-20)
    np.testing.assert_allclose(res.points[:, 1], Y, rtol=1e-10, atol=1e-20)
    np.testing.assert_allclose(res.pressure, P, rtol=1e-10, atol=1e-3)


# --- Excel and hand-written CSVs -----------------------------------------------------------

def test_plain_csv_reference(tmp_path):
    _check_quarter(read_result(_plain(tmp_path / "plain.csv")))


@pytest.mark.parametrize("style", ["bom", "crlf", "cr", "excel-de", "tabs", "quoted"])
def test_spreadsheet_csv_reads_as_the_plain_file(tmp_path, style):
    """A UTF-8 byte-order mark before '# force' gave "header has 1 columns"; CRLF and CR
    line ends, semicolons with decimal commas, tabs, quoted headers with units and
    metadata cells padded with empty cells (Excel's "# force = 25;;") all read."""
    meta = [f"# force = {FORCE_MM}", "# units = mm"]
    if style == "bom":
        lines, kw = [*meta, "x,y,p", *_rows()], {"bom": True}
    elif style == "crlf":
        lines, kw = [*meta, "x,y,p", *_rows()], {"newline": "\r\n", "bom": True}
    elif style == "cr":
        lines, kw = [*meta, "x,y,p", *_rows()], {"newline": "\r"}
    elif style == "excel-de":
        lines = [f"# force = {FORCE_MM};;", ";;", '"x [mm]";"y [mm]";"p [MPa]"',
                 *_rows(";", decimal=","), ";;"]
        kw = {"newline": "\r\n", "bom": True}
    elif style == "tabs":
        lines, kw = [*meta, "x (mm)\ty (mm)\tp (MPa)", *_rows("\t", decimal=",")], {}
    else:
        lines = [f'"# force = {FORCE_MM}",,', '"x [mm]","y [mm]","p [N/mm^2]"',
                 *(",".join(f'"{c}"' for c in row.split(",")) for row in _rows())]
        kw = {"newline": "\r\n"}
    _check_quarter(read_result(_write(tmp_path / f"{style}.csv", lines, **kw)))


@pytest.mark.parametrize("header", ["x [mm],y [mm],p [MPa]", "x (mm),y (mm),p (MPa)",
                                    "x_mm,y_mm,pressure_MPa", "x/mm,y/mm,CPRESS/MPa",
                                    "X [MM],Y [MM],P [MPA]"])
@pytest.mark.parametrize("units", [None, "mm"])
def test_units_in_column_names_agreeing_are_read(tmp_path, header, units):
    """Columns named with their units in mm, N, MPa are read as such with --units mm, and
    choose mm where neither --units nor a '# units' line says (they were read as SI)."""
    path = _write(tmp_path / "u.csv", [f"# force = {FORCE_MM}", header, *_rows()])
    res = read_result(path, units=units)
    _check_quarter(res)
    assert res.details["units"] == "mm"


def test_units_in_column_names_in_si(tmp_path):
    path = _write(tmp_path / "si.csv", [f"# force = {FORCE_MM}", "x [m],y [m],p [Pa]",
                                        *_rows(length=1.0, pressure=1.0)])
    _check_quarter(read_result(path))
    _check_quarter(read_result(path, units="SI"))


@pytest.mark.parametrize("header,units,words", [
    ("x [mm],y [mm],p [MPa]", "SI", ("'x [mm]'", "mm", "--units says SI")),
    ("x [m],y [m],p [Pa]", "mm", ("'x [m]'", "SI", "--units says mm")),
    ("x,y,pressure_MPa", "SI", ("'pressure_MPa'", "mm", "--units says SI")),
    ("x [mm],y [mm],p [kPa]", None, ("'p [kPa]'", "'kpa'", "Pa (SI) or MPa (mm)")),
    ("x [um],y [um],p [MPa]", "mm", ("'x [um]'", "'um'", "m (SI) or mm (mm)")),
    ("x [mm],y [mm],p [Pa]", None, ("two systems", "'p [Pa]'", "'x [mm]'")),
])
def test_units_in_column_names_contradicting_are_refused(tmp_path, header, units, words):
    path = _write(tmp_path / "bad.csv", [f"# force = {FORCE_MM}", header, *_rows()])
    with pytest.raises(ResultError) as err:
        read_result(path, units=units)
    msg = str(err.value)
    assert msg.startswith(f"{path}, line 2: ") and "\n" not in msg
    for w in words:
        assert w in msg


def test_units_line_contradicting_a_column_is_refused(tmp_path):
    path = _write(tmp_path / "line.csv", ["# units = SI", "approach [mm],force [N]",
                                          "0,0", "0.01,5"])
    with pytest.raises(ResultError, match=r"line\.csv, line 2: column 'approach \[mm\]' .*"
                                          r"'# units' line \(line 1\) says SI"):
        read_force_approach(path)
    _write(path, ["approach [mm],force [N]", "0,0", "0.01,5"])
    approach, force, units = read_force_approach(path)
    assert units == "mm" and approach[1] == pytest.approx(1e-5, rel=1e-15)


def test_meta_force_with_another_unit_is_refused(tmp_path):
    path = _write(tmp_path / "kn.csv", ["# force = 0.025 kN", "# units = mm", "x,y,p",
                                        *_rows()])
    with pytest.raises(ResultError, match=r"kn\.csv, line 1, force: .*in N, not 'kN'"):
        read_result(path)
    _write(path, ["# force = 25 N", "# units = mm", "x,y,p", *_rows()])
    _check_quarter(read_result(path))


# --- sizes: huge cells, huge files, /dev/zero ------------------------------------------------

def _tangential_files(tmp_path, surface_meta=(), history_rows=None):
    s, h = tmp_path / "surface.csv", tmp_path / "history.csv"
    defaults = ["# mu = 0.3", "# normal_force = 25", "# units = mm"]
    lines, seen = list(defaults), set()
    for meta in surface_meta:  # the first line of a key replaces its default; more follow
        key = meta.split("=")[0]
        at = next((k for k, line in enumerate(defaults) if line.split("=")[0] == key), None)
        if at is not None and key not in seen:
            lines[at] = meta
        else:
            lines.append(meta)
        seen.add(key)
    lines.append("x,y,p,qx,qy")
    lines += [row + ",0,0" for row in _rows()]
    _write(s, lines)
    rows = history_rows or ["0,0", "0.0001,2", "0.0002,4", "0.0001,1", "-0.0002,-4"]
    _write(h, ["# units = mm", "displacement,force", *rows])
    return s, h


def _four_readers(tmp_path):
    """(name, path, read) of each CSV reader on a valid file of its kind."""
    fa = _write(tmp_path / "fa.csv", ["approach,force", "0,0", "1e-6,3"])
    s, h = _tangential_files(tmp_path)
    return [("surface", _plain(tmp_path / "plain.csv"), read_result),
            ("force-approach", fa, read_force_approach),
            ("history", h, read_history),
            ("tangential", s, lambda p: read_tangential(p, h))]


def test_the_valid_files_of_the_four_readers_read(tmp_path):
    for _, path, read in _four_readers(tmp_path):
        read(path)


@pytest.mark.parametrize("where", ["header", "row"])
def test_a_cell_over_the_csv_field_limit_is_one_error(tmp_path, where):
    """A quoted cell of 131,073 characters ended in _csv.Error (field larger than field
    limit) in all four CSV readers."""
    for name, path, read in _four_readers(tmp_path):
        lines = path.read_text().splitlines()
        k = next(i for i, line in enumerate(lines) if not line.startswith("#"))
        k += 1 if where == "row" else 0
        lines[k] = '"' + "7" * 131_073 + '",' + lines[k]
        _write(path, lines)
        with pytest.raises(ResultError) as err:
            read(path)
        assert str(err.value).startswith(f"{path}, line {k + 1}: "), name


def test_a_file_of_zeros_is_refused_in_little_memory(tmp_path):
    """A 2 GB file of zero bytes peaked at 4.3 GB read as .csv: it is refused at its first
    line, having read one line's worth (here 40 MB of zeros, under 1 MB traced)."""
    path = tmp_path / "zeros.csv"
    with open(path, "wb") as f:
        f.truncate(40 << 20)
    tracemalloc.start()
    try:
        for read in (read_result, read_force_approach, read_history):
            with pytest.raises(ResultError, match=r"zeros\.csv, line 1: longer than"):
                read(path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 1 << 20


def test_dev_zero_is_refused(tmp_path):
    with pytest.raises(ResultError, match=r"/dev/zero, line 1: longer than"):
        read_force_approach("/dev/zero")


def test_rows_beyond_the_cap_are_refused(tmp_path, monkeypatch):
    monkeypatch.setattr(table_module, "MAX_ROWS", 50)
    path = _plain(tmp_path / "many.csv")  # 81 rows from line 4
    with pytest.raises(ResultError, match=r"many\.csv, line 54: more than 50 data rows"):
        read_result(path)
    monkeypatch.setattr(table_module, "MAX_LINES", 20)
    _write(path, [""] * 30)
    with pytest.raises(ResultError, match=r"many\.csv: more than 20 lines"):
        read_result(path)


# --- geometry that no triangulation takes -----------------------------------------------------

def _scaled(tmp_path, name, x, y):
    rows = [f"{a!r},{b!r},{p!r}" for a, b, p in zip(x.tolist(), y.tolist(), P.tolist(),
                                                   strict=True)]
    return _write(tmp_path / name, ["# force = 25", "x,y,p", *rows])


@pytest.mark.parametrize("case,words", [
    ("collinear", "lie on one line"), ("diagonal", "lie on one line"),
    ("x1e300", "are the units right"), ("x1e-300", "are the units right"),
    ("far", "too far for double precision")])
def test_degenerate_csv_geometry_is_one_error(tmp_path, case, words):
    """Collinear nodes and coordinates times 1e+-300 ended in a QhullError traceback (or
    a failed SVD); a surface 1e7 of its size from the origin cannot be triangulated
    either."""
    x, y = {"collinear": (X, 0 * Y), "diagonal": (X, 2 * X), "x1e300": (X * 1e300, Y * 1e300),
            "x1e-300": (X * 1e-300, Y * 1e-300), "far": (X + 1e5, Y)}[case]
    path = _scaled(tmp_path, f"{case}.csv", x, y)
    with pytest.raises(ResultError, match=rf"^{path}: .*{words}"):
        read_result(path)


def test_a_frame_whose_normal_lies_in_the_surface_is_refused():
    """Given a frame seen edge-on, the in-plane coordinates lie on a line: refused at
    construction, not by qhull in the grader."""
    pts = np.column_stack([X, Y, 0 * X])
    frame = ContactFrame(normal=[0.0, 1.0, 0.0], x_axis=[1.0, 0.0, 0.0])
    with pytest.raises(ResultError, match=r"^run\.csv: field 'frame'.*lie on one line"):
        ContactResult(points=pts, pressure=P, force=1.0, frame=frame, source="run.csv")


# --- meshio files with broken cells and points ----------------------------------------------

def _vtu(path, points, cells, fields=None):
    meshio.write(path, meshio.Mesh(points, [("triangle", cells)],
                                   point_data=fields or {"CPRESS": P}), binary=False)
    return path


def _grid_triangles():
    n = len(_G)
    k = np.arange(n * n).reshape(n, n)
    a, b, c, d = k[:-1, :-1].ravel(), k[:-1, 1:].ravel(), k[1:, :-1].ravel(), k[1:, 1:].ravel()
    return np.concatenate([np.column_stack([a, b, d]), np.column_stack([a, d, c])])


POINTS = np.column_stack([X, Y, 0 * X])
TRIANGLES = _grid_triangles()


def test_vtu_reference_reads(tmp_path):
    res = read_result(_vtu(tmp_path / "good.vtu", POINTS, TRIANGLES), force=25.0)
    assert res.symmetry == "quarter" and res.force == pytest.approx(100.0, rel=1e-15)


@pytest.mark.parametrize("case,words", [
    ("past", "has node index 84; the mesh has 81 points"),
    ("negative", "has node index -1; the mesh has 81 points"),
    ("very negative", "has node index -81; the mesh has 81 points"),
    ("one column", "2 or 3 coordinates each, got an array of shape (81, 1)"),
    ("nan", "1 point(s) with a non-finite coordinate, first point 40"),
    ("x1e300", "are the units right"), ("x1e-300", "are the units right"),
    ("collinear", "lie on one line")])
def test_vtu_broken_cells_and_points_are_one_error(tmp_path, case, words):
    """A cell index past the last point and one coordinate column gave IndexError; a
    NEGATIVE index wrapped silently to the last points and graded PASSED; NaN coordinates
    gave "SVD did not converge" without the file; scaled or collinear points, QhullError."""
    pts, tri = POINTS.copy(), TRIANGLES.copy()
    if case == "past":
        tri[7, 1] = 84
    elif case == "negative":
        tri[7, 1] = -1
    elif case == "very negative":
        tri[7, 1] = -81
    elif case == "one column":
        pts = pts[:, :1]
    elif case == "nan":
        pts[40, 0] = np.nan
    elif case == "x1e300":
        pts *= 1e300
    elif case == "x1e-300":
        pts *= 1e-300
    else:
        pts[:, 1] = 0.0
    path = _vtu(tmp_path / "bad.vtu", pts, tri)
    with pytest.raises(ResultError) as err:
        read_result(path, force=25.0)
    assert str(err.value).startswith(f"{path}: ") and words in str(err.value)


def test_vtu_field_of_the_wrong_length_is_one_error(tmp_path):
    path = tmp_path / "short.vtu"
    mesh = meshio.Mesh(POINTS, [("triangle", TRIANGLES)], point_data={"CPRESS": P})
    meshio.write(path, mesh, binary=False)
    text = path.read_text()
    head, _, rest = text.partition('Name="CPRESS"')
    body, end, tail = rest.partition("</DataArray>")
    numbers = body.split(">", 1)
    path.write_text(head + 'Name="CPRESS"' + numbers[0] + ">"
                    + " ".join(numbers[1].split()[:-3]) + "\n" + end + tail)
    try:
        read_result(path, force=25.0)
    except ResultError as exc:
        assert str(exc).startswith(f"{path}: ")
    else:  # pragma: no cover - meshio may pad or refuse; a silent result must not come out
        pytest.fail("a pressure field shorter than the points was read")


# --- the tangential CSV ------------------------------------------------------------------

@pytest.mark.parametrize("value,words", [
    ("inf", "must be a finite number"), ("nan", "must be a finite number"),
    ("-inf", "must be a finite number"), ("1e400", "must be a finite number"),
    ("2.5", "must be an integer"), ("99", "an index 1..4 into the path of 5 points"),
    ("0", "an index 1..4"), ("three", "is not a number")])
def test_tangential_snapshot_line(tmp_path, value, words):
    """'# snapshot = inf' ended in OverflowError; 'nan' in a ValueError naming no file."""
    s, h = _tangential_files(tmp_path, [f"# snapshot = {value}"])
    with pytest.raises(ResultError) as err:
        read_tangential(s, h)
    assert str(err.value).startswith(f"{s}, line 4") and words in str(err.value)


@pytest.mark.parametrize("key,value", [("mu", "nan"), ("mu", "inf"), ("mu", "-0.3"),
                                       ("direction_deg", "inf"), ("normal_force", "nan")])
def test_tangential_meta_numbers_not_finite_name_the_line(tmp_path, key, value):
    s, h = _tangential_files(tmp_path, [f"# {key} = {value}"])
    line = {"mu": 1, "normal_force": 2}.get(key, 4)
    with pytest.raises(ResultError, match=rf"^{s}, line {line}[:,] {key}"):
        read_tangential(s, h)


@pytest.mark.parametrize("rows,words", [
    (["0.001,0", "0.002,1"], ("must start at 0", "line 3")),
    (["0,0", "-0.001,-1", "0.001,1"], ("must rise first", "line 4")),
    (["0,0"], ("2 or more points",)),
    (["0,0", "0,0"], ("never leaves 0",)),
    (["0,0", "0.001,nan"], ("non-finite", "line 4")),
])
def test_tangential_history_errors_name_the_history_file(tmp_path, rows, words):
    """A bad path was reported against the SURFACE file (the TangentialResult's source)."""
    s, h = _tangential_files(tmp_path, history_rows=rows)
    with pytest.raises(ResultError) as err:
        read_tangential(s, h)
    msg = str(err.value)
    assert msg.startswith(f"{h}") and str(s) not in msg
    for w in words:
        assert w in msg


def test_tangential_reference_reads(tmp_path):
    s, h = _tangential_files(tmp_path, ["# snapshot = 2"])
    r = read_tangential(s, h)
    assert isinstance(r, TangentialResult) and r.snapshot == 2
    np.testing.assert_allclose(r.displacement, [0, 1e-7, 2e-7, 1e-7, -2e-7], rtol=1e-12)
    np.testing.assert_allclose(r.force, 4 * np.array([0, 2, 4, 1, -4]), rtol=1e-15)
    assert r.normal_force == pytest.approx(100.0, rel=1e-15)


# --- fuzz ----------------------------------------------------------------------------------

def _mutations(data: bytes, rng: random.Random, count: int):
    """Seeded damage: cuts, byte flips, huge and odd fields, doubled and dropped lines."""
    for _ in range(count):
        kind = rng.randrange(6)
        if kind == 0:
            yield data[:rng.randrange(len(data))]
        elif kind == 1:
            b = bytearray(data)
            for _ in range(rng.randint(1, 6)):
                b[rng.randrange(len(b))] = rng.randrange(256)
            yield bytes(b)
        elif kind == 2:
            at = rng.randrange(len(data))
            yield data[:at] + rng.choice([b"9" * 140_000, b'"' + b"x" * 140_000 + b'"',
                                          b"\x00" * 70_000]) + data[at:]
        elif kind == 3:
            at = rng.randrange(len(data))
            yield data[:at] + rng.choice([b"nan", b"inf", b"-1e999", b";", b'"', b"\r",
                                          b"\n\n", b",", b"\xef\xbb\xbf", b"1e-320", b"-",
                                          b"-0", b"# units = mm\n", b"\xff"]) + data[at:]
        elif kind == 4:
            lines = data.split(b"\n")
            k = rng.randrange(len(lines))
            yield b"\n".join(lines[:k] + [lines[k]] * rng.randint(2, 5) + lines[k + 1:])
        else:
            lines = data.split(b"\n")
            k = rng.randrange(len(lines))
            yield b"\n".join(lines[:k] + lines[k + 1:])


def _fuzz(path, read, count, seed):
    data = path.read_bytes()
    rng = random.Random(seed)
    outcomes = {"result": 0, "error": 0}
    for k, damaged in enumerate(_mutations(data, rng, count)):
        path.write_bytes(damaged)
        try:
            read(path)
        except ValueError as exc:
            assert str(path) in str(exc), (k, str(exc))
            assert "\n" not in str(exc), (k, str(exc))
            outcomes["error"] += 1
        else:
            outcomes["result"] += 1
    return outcomes


@pytest.mark.parametrize("reader", ["surface", "force-approach", "history", "tangential"])
def test_fuzz_csv_readers(tmp_path, reader):
    """A seeded fuzz of each CSV reader: every outcome is a result or one ValueError naming
    the file; never another exception."""
    name, path, read = next(r for r in _four_readers(tmp_path) if r[0] == reader)
    out = _fuzz(path, read, 120, seed=22 + len(reader))
    assert out["error"] > 0 and out["result"] > 0  # the fuzz both broke and spared files


@pytest.mark.parametrize("binary", [False, True])
def test_fuzz_vtu_reader(tmp_path, binary):
    path = tmp_path / "f.vtu"
    meshio.write(path, meshio.Mesh(POINTS, [("triangle", TRIANGLES)],
                                   point_data={"CPRESS": P}), binary=binary)
    out = _fuzz(path, lambda p: read_result(p, force=25.0), 80, seed=7 + binary)
    assert out["error"] > 0


def test_latin1_text_names_its_line(tmp_path):
    """Excel's "CSV (Comma delimited)" writes Windows-1252: the first line that is not
    UTF-8 is named, not the line the reader had decoded ahead to."""
    path = tmp_path / "latin.csv"
    lines = ["approach,force", *["1e-6,1"] * 3000, "1e-6,1 \u00b0"]
    path.write_bytes("\n".join(lines).encode("cp1252"))
    with pytest.raises(ResultError, match=r"latin\.csv, line 3002: not UTF-8 text \(byte 0xb0\)"):
        read_force_approach(path)


def test_a_device_is_not_a_result_file():
    with pytest.raises(ResultError, match=r"^/dev/zero: not a regular file"):
        read_result("/dev/zero")


# --- compressed .vtu: a zip bomb is refused before it inflates (audit of issue 22, item 10) ---

_BOMB = 64 << 20  # bytes of zeros the bomb's CPRESS inflates to (a grid of 81 points needs 648)


def _packed(data: bytes, codec, block: int, declare: int | None = None) -> tuple[bytes, bytes]:
    """(header, blocks) of a VTK compressed array: [blocks, block size, last size, packed
    sizes...] as UInt32; ``declare`` replaces the inflated sizes the header gives."""
    chunks = [data[i:i + block] for i in range(0, len(data), block)] or [b""]
    packed = [codec.compress(c) for c in chunks]
    full, last = (block, len(chunks[-1])) if declare is None else (declare, declare)
    if declare is not None and len(chunks) == 1:
        full = declare
    header = np.array([len(chunks), full, last, *map(len, packed)], dtype="<u4").tobytes()
    return header, b"".join(packed)


def _compressed_vtu(path, compression, layout, bomb=None, declare=None):
    """The grid's .vtu written by meshio (compressed, inline base64), then its CPRESS array
    replaced by ``bomb`` bytes (with ``declare`` as its header's sizes), and its arrays
    moved to appended data where ``layout`` says ("raw" or "base64")."""
    import base64
    import lzma
    import re
    import zlib

    codec = {"zlib": zlib, "lzma": lzma}[compression]
    mesh = meshio.Mesh(POINTS, [("triangle", TRIANGLES)], point_data={"CPRESS": P})
    meshio.write(path, mesh, binary=True, compression=compression)
    text = path.read_text()
    arrays = []

    def take(m):
        attrs, body = m.group(1), m.group(2).strip()
        if 'Name="CPRESS"' in attrs and bomb is not None:
            header, blocks = _packed(bomb, codec, len(bomb), declare)
        else:
            n = len(base64.b64decode(body[:8])[:4])
            count = int(np.frombuffer(base64.b64decode(body[:8])[:n], "<u4")[0])
            chars = -(-(3 + count) * 4 // 3) * 4
            header = base64.b64decode(body[:chars])[:(3 + count) * 4]
            blocks = base64.b64decode(body[chars:])
        arrays.append((header, blocks))
        if layout == "inline":
            return (f"<DataArray{attrs}>" + base64.b64encode(header).decode()
                    + base64.b64encode(blocks).decode() + "</DataArray>")
        return f'<DataArray{attrs.replace("binary", "appended")} offset="@{len(arrays) - 1}@"/>'

    text = re.sub(r"<DataArray([^>]*)>(.*?)</DataArray>", take, text, flags=re.S)
    if layout == "inline":
        path.write_text(text)
        return path
    pieces, offsets, at = [], [], 0
    for header, blocks in arrays:
        piece = header + blocks if layout == "raw" else \
            (base64.b64encode(header) + base64.b64encode(blocks))
        offsets.append(at)
        at += len(piece)
        pieces.append(piece)
    for k, off in enumerate(offsets):
        text = text.replace(f'offset="@{k}@"', f'offset="{off}"')
    head, _, tail = text.rpartition("</VTKFile>")
    path.write_bytes(head.encode() + f'<AppendedData encoding="{layout}">\n_'.encode()
                     + b"".join(pieces) + b"\n</AppendedData>\n" + (_ + tail).encode())
    return path


@pytest.mark.parametrize("layout", ["inline", "base64", "raw"])
@pytest.mark.parametrize("compression", ["zlib", "lzma"])
def test_compressed_vtu_reads(tmp_path, compression, layout):
    """The layouts the bomb check parses (inline base64, appended base64, appended raw),
    compressed with zlib and lzma, read as the plain file does."""
    plain = read_result(_vtu(tmp_path / "plain.vtu", POINTS, TRIANGLES), force=25.0)
    res = read_result(_compressed_vtu(tmp_path / "good.vtu", compression, layout), force=25.0)
    assert res.symmetry == "quarter"
    np.testing.assert_allclose(res.points, plain.points, rtol=1e-10, atol=0)  # ascii: rounded
    np.testing.assert_allclose(res.pressure, plain.pressure, rtol=1e-10, atol=0)


@pytest.mark.parametrize("layout", ["inline", "base64", "raw"])
@pytest.mark.parametrize("compression", ["zlib", "lzma"])
@pytest.mark.parametrize("honest", [True, False])
def test_compressed_vtu_bomb_is_refused_before_it_inflates(tmp_path, compression, layout,
                                                           honest):
    """A CPRESS that inflates to 64 MiB of zeros (the audit's bomb: 3 GiB from a 4 MB file,
    3.2 GB of memory): a header that declares it is refused by the sizes a grid of 81
    points can need; one that declares 648 bytes is refused as its block inflates past
    them.  Nothing near the bomb's size is allocated."""
    import tracemalloc

    bomb = bytes(_BOMB)
    path = _compressed_vtu(tmp_path / "bomb.vtu", compression, layout, bomb,
                           declare=None if honest else 8 * len(P))
    del bomb
    words = "refused before inflating" if honest else "inflates past the 648 bytes"
    tracemalloc.start()
    try:
        with pytest.raises(ResultError, match=words) as err:
            read_result(path, force=25.0)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    message = str(err.value)
    assert message.startswith(f"{path}: DataArray 'CPRESS'") and "\n" not in message
    assert peak < 16 << 20, peak


# --- the frame: huge, zero and subnormal vectors, a far origin (audit, items 12 and 13) ---------

@pytest.mark.parametrize("part,value,words", [
    ("normal", [0.0, 0.0, 0.0], r"field 'frame\.normal' must be a nonzero vector"),
    ("x_axis", [0.0, 0.0, 0.0], r"field 'frame\.x_axis' must be a nonzero vector"),
    ("origin", [1e308, 0.0, 0.0], r"field 'frame\.origin': a coordinate is 1e\+308 m"),
    ("origin", [1e5, 0.0, 0.0], r"field 'frame\.origin' .* lies 100000 m from nodes"),
])
def test_frame_parts_out_of_range_are_one_error(tmp_path, part, value, words):
    """--normal 0,0,0 blamed the origin after a RuntimeWarning (NaN); --origin 1e308,0,0
    ended in "SVD did not converge"; an origin 1e5 m off, a RuntimeWarning in the grader."""
    import warnings

    path = _plain(tmp_path / "plain.csv")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ResultError, match=rf"^{path}: {words}") as err:
            read_result(path, frame={part: value})
    assert "\n" not in str(err.value)


@pytest.mark.parametrize("part,value", [
    ("normal", [0.0, 0.0, 5e-324]), ("normal", [0.0, 0.0, 1e308]),
    ("normal", [1e-320, 1e-320, 1e308]), ("x_axis", [1e308, 0.0, 0.0]),
    ("x_axis", [5e-324, 0.0, 0.0])])
def test_frame_directions_of_huge_or_subnormal_components(tmp_path, part, value):
    """A direction is its direction at any scale: --normal 1e308,1e308,1e308 said "must be
    a nonzero vector, got [0, 0, 0]" (its norm overflowed), 0,0,5e-324 gave NaN."""
    import warnings

    path = _plain(tmp_path / "plain.csv")
    reference = read_result(path)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = read_result(path, frame={part: value})
    np.testing.assert_array_equal(res.frame.normal, reference.frame.normal)
    np.testing.assert_array_equal(res.frame.x_axis, reference.frame.x_axis)
    skew = ContactFrame(normal=[1e308, 1e308, 1e308], x_axis=[1e308, -1e308, 0.0])
    np.testing.assert_allclose(skew.normal, np.full(3, 3 ** -0.5), rtol=1e-15)
    np.testing.assert_allclose(skew.x_axis, [2 ** -0.5, -2 ** -0.5, 0.0], rtol=1e-15, atol=1e-16)


# --- contradicting '#' lines (audit, item 17) ------------------------------------------------

@pytest.mark.parametrize("lines,words", [
    (["# force = 5", "# force = 1000"], r"lines 1 and 2: two '# force' lines contradict each "
                                        r"other \('5', then '1000'\)"),
    (["# units = mm", "# force = 25", "# units = SI"], r"lines 1 and 3: two '# units' lines"),
])
def test_contradicting_meta_lines_are_refused(tmp_path, lines, words):
    """The last one silently won."""
    path = _write(tmp_path / "twice.csv", [*lines, "x,y,p", *_rows()])
    with pytest.raises(ResultError, match=rf"^{path}, {words}"):
        read_result(path)


def test_repeated_meta_lines_that_agree_are_read(tmp_path):
    """The same value twice (1000 and 1e3 are one number), or a key no reader uses, is
    harmless."""
    path = _write(tmp_path / "twice.csv", [f"# force = {FORCE_MM}", f"# force = {FORCE_MM:e}",
                                           "# units = mm", "# units = MM", "# note: a",
                                           "# note: b", "x,y,p", *_rows()])
    _check_quarter(read_result(path))


def test_contradicting_meta_lines_in_the_tangential_and_force_approach_files(tmp_path):
    s, h = _tangential_files(tmp_path, surface_meta=["# mu = 0.5", "# mu = 0.4"])
    with pytest.raises(ResultError, match=rf"^{s}, lines 1 and 4: two '# mu' lines"):
        read_tangential(s, h)
    fa = _write(tmp_path / "fa.csv", ["# units = mm", "# units = SI", "approach,force", "0,0",
                                      "1e-3,3"])
    with pytest.raises(ResultError, match=rf"^{fa}, lines 1 and 2: two '# units' lines"):
        read_force_approach(fa)
