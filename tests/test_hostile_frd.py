"""Hostile and malformed CalculiX input: the .frd reader, problem.json, the grade command.

Every malformed file gives one ValueError (FrdFormatError or ResultError) on one line that
names the file and the line, record or key; nothing is allocated for a count the file
cannot hold; nothing is read whole.  The documented grading command of a CalculiX run
(docs/howto/calculix.md) is run exactly as written.  Issue 22, items 3, 5 (.frd), 6 and 8.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scene_files import ball_on_plane

from fem_validation.memory import peak_mb, reset_peak
from fem_validation.readers import read_result
from fem_validation.readers.calculix import read_calculix
from fem_validation.readers.calculix_friction import read_calculix_tangential
from fem_validation.readers.frd import FrdFormatError, read_frd

DATA = Path(__file__).parent / "data" / "calculix"
ASCII = ["two_cubes.frd", "tet_cubes.frd", "tet_cubes_friction.frd"]
ALL = [*ASCII, "two_cubes_binary.frd"]

#: A sphere on a plane whose Hertz contact (a = 1.42 mm at 4378 N, steel on steel) is about
#: the size of tet_cubes' interface read as a quarter model (2 mm square): near enough for
#: the grader to grade it (a flat punch, so its pressure checks fail) instead of refusing it.
CUBES_SCENE = ball_on_plane("sphere R 100 mm on a plane, sized to the cubes' interface",
                            4378.0, radius=0.1)

#: problem.json as fem_validation.decks writes it, for the deck-run layout (run/hertz.frd).
PROBLEM = {"units": {"length": "mm", "force": "N", "stress": "MPa"},
           "frame": {"origin": [0.0, 0.0, 1.0], "normal_into_body1": [0.0, 0.0, 1.0],
                     "body1_x_axis": [1.0, 0.0, 0.0]},
           "model": {"geometry": "two cubes", "level": 0},
           "contact": {"slave": "CONTACT1", "penalty_factor": 1.0}}


def _run(tmp_path, name="tet_cubes", problem=None) -> Path:
    """A copy of a committed run laid out as `deck` writes one: run/hertz.frd, .inp, .json."""
    run = tmp_path / "run"
    run.mkdir(parents=True)
    shutil.copy(DATA / f"{name}.frd", run / "hertz.frd")
    shutil.copy(DATA / f"{name}.inp", run / "hertz.inp")
    if problem is not None:
        (run / "problem.json").write_text(problem if isinstance(problem, str)
                                          else json.dumps(problem))
    return run / "hertz.frd"


def _one_line_naming(exc: pytest.ExceptionInfo, path) -> str:
    message = str(exc.value)
    assert "\n" not in message and str(path) in message, message
    return message


# --- item 3: the documented grading command ----------------------------------------------

def _grade_command(frd: Path, scene: Path, out: Path) -> subprocess.CompletedProcess:
    """docs/howto/calculix.md, step 4, as written (no --origin, --normal, --x-axis)."""
    return subprocess.run([sys.executable, "-m", "fem_validation", "grade", str(frd),
                           "--scene", str(scene), "--units", "mm", "--out", str(out)],
                          capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("with_problem", [True, False])
def test_documented_grade_command_grades_a_calculix_run(tmp_path, with_problem):
    """It exited 2, "field 'frame' must be a ContactFrame, got dict", for every .frd.

    It grades (0: passed, 1: a check failed) and writes grade.json; the force graded is
    four times body 1's summed reaction F3 (a quarter model) from the raw .frd arrays.  With
    problem.json beside the run (as `deck` writes it) the frame is the file's, and the
    command grades exactly as the documented Python route, grade(read_calculix(...), ...).
    """
    from fem_validation.decks import read_scene
    from fem_validation.grading.contact import grade

    frd = _run(tmp_path, problem=PROBLEM if with_problem else None)
    scene = tmp_path / "scene.toml"
    scene.write_text(CUBES_SCENE)
    out = tmp_path / "graded"
    run = _grade_command(frd, scene, out)
    assert run.returncode in (0, 1), run.stderr
    assert run.stderr == "" and (out / "grade.json").is_file()
    cli = json.loads((out / "grade.json").read_text())
    f = read_frd(frd)
    body1 = np.unique(f.connectivity[f.element_materials == 1])
    nodes, fz = f.field("F3")
    assert cli["symmetry"] == "quarter"
    assert cli["force"] == pytest.approx(4 * abs(fz[np.isin(nodes, body1)].sum()), rel=1e-12)
    if with_problem:
        py = grade(read_calculix(frd), read_scene(scene))
        for name, value in py.metrics.items():  # not available: NaN here, null in grade.json
            missing = value is None or np.isnan(value)
            assert cli[name] == (None if missing else pytest.approx(value, rel=1e-12)), name


def test_partial_frame_is_completed(tmp_path):
    """Parts of the frame given, the rest problem.json's, else found from the pressed slave
    nodes: their plane is the cubes' interface z = 1 mm (tet_cubes.inp), normal +z."""
    frd = _run(tmp_path)
    found = read_result(frd, units="mm", frame={"normal": [0.0, 0.0, 1.0]}).frame
    np.testing.assert_allclose(found.origin, [0, 0, 1e-3], atol=1e-15)
    np.testing.assert_array_equal(found.x_axis, [1, 0, 0])
    alone = read_result(frd, units="mm", frame={}).frame  # nothing given: all found
    np.testing.assert_allclose(alone.origin, found.origin, atol=1e-15)
    np.testing.assert_array_equal(alone.normal, [0, 0, 1])
    (frd.parent / "problem.json").write_text(json.dumps(PROBLEM))
    # an origin given, the normal and the x axis problem.json's
    f = read_result(frd, units="mm", frame={"origin": [0.0, 0.0, 0.0]}).frame
    np.testing.assert_array_equal(f.origin, 0)
    np.testing.assert_array_equal(f.rotation, np.eye(3))
    # a normal given that problem.json's x axis is not orthogonal to: that axis is found
    f = read_result(frd, units="mm", frame={"normal": [0.6, 0.0, 0.8]}).frame
    assert abs(f.normal @ f.x_axis) < 1e-15 and f.origin[2] == 1e-3
    # the frictional reader takes the same dict
    fr = _run(tmp_path / "friction", "tet_cubes_friction")
    t = read_calculix_tangential(fr, symmetry="whole", frame={"normal": [0.0, 0.0, 1.0]})
    np.testing.assert_allclose(t.frame.origin[2], 1e-3, atol=1e-15)


# --- item 6: the .frd reader on malformed files ------------------------------------------

@pytest.mark.parametrize("name", ASCII)
@pytest.mark.parametrize("key", [b"    2C", b"    3C", b"\n -4"])
def test_cut_just_after_a_key(tmp_path, name, key):
    """A file cut just after a 2C, 3C or -4 key raised IndexError."""
    data = (DATA / name).read_bytes()
    path = tmp_path / name
    for extra in (0, 1):
        path.write_bytes(data[:data.index(key) + len(key) + extra])
        with pytest.raises(FrdFormatError) as exc:
            read_frd(path)
        assert re.search(r": line \d+: ", _one_line_naming(exc, path))


def _node_lines(text: str) -> list[str]:
    start = text.index("    2C")
    return text[start:text.index(" -3", start)].splitlines()[1:]


@pytest.mark.parametrize("how", ["replace", "add"])
def test_duplicated_node_number(tmp_path, how):
    """A node number given twice was silently accepted (the second coordinates won) or gave
    KeyError; the node block's count adjusted so that only the repeat is wrong."""
    text = (DATA / "tet_cubes.frd").read_text()
    nodes = _node_lines(text)
    second = nodes[4][:3] + nodes[1][3:13] + nodes[4][13:]  # node 5's record says node 2
    if how == "replace":
        text = text.replace(nodes[4] + "\n", second + "\n", 1)
    else:
        text = text.replace(nodes[4] + "\n", nodes[4] + "\n" + second + "\n", 1)
        text = text.replace("    2C                            54",
                            "    2C                            55", 1)
    path = tmp_path / "dup.frd"
    path.write_text(text)
    with pytest.raises(FrdFormatError, match=r"line 14: node 2 appears twice") as exc:
        read_frd(path)
    _one_line_naming(exc, path)


def test_duplicated_node_in_binary_block(tmp_path):
    data = bytearray((DATA / "two_cubes_binary.frd").read_bytes())
    start = data.index(b"    2C")
    first = data.index(b"\n", start) + 1
    # node records: 4-byte number, three 8-byte coordinates (format 3); the third says 1
    data[first + 2 * 28:first + 2 * 28 + 4] = np.int32(1).tobytes()
    path = tmp_path / "dup.frd"
    path.write_bytes(bytes(data))
    with pytest.raises(FrdFormatError, match=r"node 1 appears twice \(records 1 and 3"):
        read_frd(path)


def test_result_for_a_node_not_in_the_node_block(tmp_path):
    """A stress for node 999 (there are 54 nodes) gave KeyError in the reader."""
    text = (DATA / "tet_cubes.frd").read_text()
    start = text.index(" -4  STRESS")
    record = text.index(" -1         1", start)
    text = text[:record] + " -1       999" + text[record + 13:]
    path = tmp_path / "stranger.frd"
    path.write_text(text)
    line = text[:start].count("\n")  # the STRESS set's 100C line
    with pytest.raises(FrdFormatError,
                       match=rf"line {line}: result set STRESS refers to node 999, which is "
                             r"not in the node block"):
        read_frd(path)


def test_element_with_a_node_not_in_the_node_block(tmp_path):
    text = (DATA / "tet_cubes.frd").read_text()
    start = text.index("    3C")
    nodes = text.index(" -2", start)
    text = text[:nodes] + " -2      9999" + text[nodes + 13:]
    path = tmp_path / "stranger.frd"
    path.write_text(text)
    with pytest.raises(FrdFormatError, match=r"line 70: the element block refers to node "
                                             r"9999"):
        read_frd(path)


def test_missing_stress_component_names_file_and_set(tmp_path):
    """No SZX in the STRESS set: "tuple.index(x): x not in tuple", no file named."""
    frd = _run(tmp_path)
    text = frd.read_text()
    frd.write_text(text.replace(" -5  SZX ", " -5  SQQ ", 1))
    line = text[:text.index(" -4  STRESS")].count("\n")
    with pytest.raises(ValueError, match=rf"line {line}: result set STRESS has no component "
                                         r"'SZX'") as exc:
        read_calculix(frd, units="mm")
    _one_line_naming(exc, frd)


def test_missing_friction_components_name_file_and_set(tmp_path):
    frd = _run(tmp_path, "tet_cubes_friction")
    frd.write_text(frd.read_text().replace(" -5  CSHEAR1 ", " -5  CSHEARX "))
    with pytest.raises(ValueError, match=r"result set CONTACT has no component 'CSHEAR1'") \
            as exc:
        read_calculix_tangential(frd, symmetry="whole")
    _one_line_naming(exc, frd)


def _with_count(text: str, key: str, count: int) -> str:
    """``text`` with the count (columns 25-36) of the first ``key`` line replaced."""
    i = text.index(key)
    return text[:i + 24] + f"{count:12d}" + text[i + 36:]


@pytest.mark.parametrize("name", ["tet_cubes.frd", "two_cubes_binary.frd"])
@pytest.mark.parametrize("count", [-3, -1])
def test_negative_counts(tmp_path, name, count):
    """A negative count ended in numpy's "negative dimensions" without the file."""
    text = (DATA / name).read_bytes().decode("latin-1")
    path = tmp_path / name
    for key in ("    2C", "  100C"):
        path.write_bytes(_with_count(text, key, count).encode("latin-1"))
        with pytest.raises(FrdFormatError, match=rf"is {count}; it must be 0 or more") as exc:
            read_frd(path)
        _one_line_naming(exc, path)


@pytest.mark.parametrize("name", ["tet_cubes.frd", "two_cubes_binary.frd"])
def test_count_beyond_the_file_allocates_nothing(tmp_path, name):
    """A result set announcing 1e11 nodes allocated 745 GiB before reading a record."""
    text = (DATA / name).read_bytes().decode("latin-1")
    path = tmp_path / name
    for key in ("    2C", "    3C", "  100C"):
        path.write_bytes(_with_count(text, key, 99_999_999_999).encode("latin-1"))
        reset_peak()
        before = peak_mb()
        with pytest.raises(FrdFormatError, match="cut or corrupt|ends early") as exc:
            read_frd(path)
        _one_line_naming(exc, path)
        assert peak_mb() - before < 50


def test_file_of_zeros_is_not_read_whole(tmp_path):
    """2 GB of zero bytes peaked at 4.3 GB: the first line ends the reading."""
    path = tmp_path / "zeros.frd"
    with open(path, "wb") as f:
        f.truncate(2 << 30)  # sparse: no disk, and nothing in memory unless read
    reset_peak()
    before = peak_mb()
    with pytest.raises(FrdFormatError, match=r"line 1: a line longer than 1024"):
        read_frd(path)
    assert peak_mb() - before < 50
    with pytest.raises(FrdFormatError, match=r"/dev/zero: line 1"):
        read_frd("/dev/zero")


SEVEN = """    2C                             2                                     0
 -1    1 0.00000E+00 1.00000E+00 2.00000E+00
 -1    2-1.50000E+00 2.50000E-01 3.00000E+03
 -3
  100CL  101 2.500000000           2                     0    3           0
 -4  SEVEN       7    1
 -5  C1          1    1    0    0
 -5  C2          1    1    0    0
 -5  C3          1    1    0    0
 -5  C4          1    1    0    0
 -5  C5          1    1    0    0
 -5  C6          1    1    0    0
 -5  C7          1    1    0    0
 -1    1 1.00000E+00 2.00000E+00 3.00000E+00 4.00000E+00 5.00000E+00 6.00000E+00
 -2      7.00000E+00
 -1    2-1.00000E+00-2.00000E+00-3.00000E+00-4.00000E+00-5.00000E+00-6.00000E+00
 -2     -7.00000E+00
 -3
 9999
"""


@pytest.mark.parametrize("cut, message", [
    # node 2's -1 line gone: its -2 line was taken for a node with an uninitialised number
    (lambda t: t.replace(t[t.index(" -1    2-1.0"):t.index(" -2     -7")], ""),
     r"line 16: a continuation line \(-2\) with no node record"),
    # node 1's -2 line gone: node 2's -1 line overwrote node 1's open record
    (lambda t: t.replace(" -2      7.00000E+00\n", ""), r"line 15: .*node 1 needs 1"),
    (lambda t: t.replace(" -1    2-1.50000E+00", " -1    2       nan "),
     r"line 1: node 2 \(record 2 of the block\) has a non-finite coordinate"),
    (lambda t: t.replace(" 9999", t[:t.index("  100C")] + " 9999"),
     r"line 19: a second node block \(2C\); the first is at line 1"),
    (lambda t: t.replace(" -5  C7 ", " -5  C1 "), "names its component 'C1' twice"),
    (lambda t: t.replace(" -4  SEVEN       7    1", " -4"), "-4 line needs its name"),
    (lambda t: t.replace(" -5  C3 ", " -1  C3 "),
     r"line 9: result set SEVEN: expected component line \(-5\) 3 of 7"),
    (lambda t: t.replace("0    3           0", "0    3           7"), "format is 7"),
])
def test_malformed_ascii_records(tmp_path, cut, message):
    path = tmp_path / "bad.frd"
    path.write_text(cut(SEVEN))
    with pytest.raises(FrdFormatError, match=message) as exc:
        read_frd(path)
    _one_line_naming(exc, path)


def _variants(data: bytes, rng: np.random.Generator, cases: int):
    """Cuts at and just after block keys and record starts (the first key of each kind and
    30 others drawn of each group) and at random points; copies with 1 to 3 bytes changed."""
    for pattern in (rb"2C|3C|\n -4|\n -5|100C", rb"\n -1|\n -2|\n -3"):
        ends = [m.end() for m in re.finditer(pattern, data)]
        firsts = {data[e - 2:e]: e for e in reversed(ends)}.values()
        for end in {*firsts, *rng.choice(ends, min(30, len(ends)), replace=False).tolist()}:
            yield data[:end]
            yield data[:end + 1]
    for _ in range(cases):
        yield data[:int(rng.integers(0, len(data)))]
        b = bytearray(data)
        for _ in range(int(rng.integers(1, 4))):
            i = int(rng.integers(0, len(b)))
            if rng.random() < 0.5:
                b[i] ^= 1 << int(rng.integers(0, 8))
            else:
                b[i] = int(rng.choice(list(b"0123456789-+. E\n")))
        yield bytes(b)


@pytest.mark.parametrize("name", ALL)
def test_fuzz_cuts_and_flips(tmp_path, name):
    """Cut and corrupted copies of the committed runs (seeded): each reads, or raises a
    one-line ValueError naming the .frd (or its deck) -- never another exception."""
    data = (DATA / name).read_bytes()
    stem = name.removesuffix(".frd")
    shutil.copy(DATA / f"{stem}.inp", tmp_path / f"{stem}.inp")
    path = tmp_path / name
    read = (lambda p: read_calculix_tangential(p, symmetry="whole")) if "friction" in name \
        else read_calculix
    rng = np.random.default_rng(22)
    outcomes = {"read": 0, "refused": 0}
    for variant in _variants(data, rng, 60 if "friction" in name else 100):
        path.write_bytes(variant)
        for reader in (read_frd, read):
            try:
                reader(path)
                outcomes["read"] += 1
            except ValueError as exc:
                message = str(exc)
                assert "\n" not in message and (str(path) in message or str(
                    path.with_suffix(".inp")) in message), message
                outcomes["refused"] += 1
    assert outcomes["refused"] > 100


# --- item 8: problem.json beside a .frd ---------------------------------------------------

_UNITS = '"units": {"length": "mm"}'


@pytest.mark.parametrize("text, key", [
    ('{"units": {}}', "'units.length'"),
    ("{}", "'units.length'"),
    ("[]", "JSON object"),
    ('"mm"', "JSON object"),
    ("null", "JSON object"),
    ('{"units": "mm"}', "'units' must be an object"),
    ('{"units": {"length": 3}}', "'units.length'"),
    ('{"units": {"length": "km"}}', "'units.length'"),
    ('{"units": {"length": "mm", "stress": "Pa"}}', "'units.stress'"),
    ('{"units": {"length": NaN}}', "'units.length' is NaN"),
    ('{"units": {"length": "mm"}', "line 1: not JSON"),
    ('{"units": {"length": "mm"},\n "loads": {"approach": 1e400}}', "'loads.approach'"),
    ("{" + _UNITS + ', "loads": {"approach": Infinity}}', "'loads.approach' is Infinity"),
    ("{" + _UNITS + ', "loads": {"approach": "0.01"}}', "'loads.approach'"),
    ("{" + _UNITS + ', "frame": [0, 0, 1]}', "'frame' must be an object"),
    ("{" + _UNITS + ', "frame": {"origin": [0, 0]}}', "'frame.origin'"),
    ("{" + _UNITS + ', "frame": {"origin": [0, 0, -Infinity]}}', "'frame.origin.2'"),
    ("{" + _UNITS + ', "frame": {"normal_into_body1": [0, 0, 0]}}',
     "'frame.normal_into_body1'"),
    ("{" + _UNITS + ', "frame": {"normal_into_body1": [0, 0, 1], "body1_x_axis": [0, 1, 1]}}',
     "'frame.body1_x_axis'"),
    ("{" + _UNITS + ', "loads": {"approach": 0.01}, "model": {"far_face_depths": [1]}}',
     "'model.far_face_depths'"),
    ("{" + _UNITS + ', "loads": {"approach": 0.01}, "model": {"far_face_depths": [1, 2]}}',
     "'materials'"),
    ("{" + _UNITS + ', "materials": {"body1": {"E": 1}, "body2": {"E": 1, "nu": 0.3}}}',
     "'materials.body1'"),
    ("{" + _UNITS + ', "materials": {"body1": {"E": -1, "nu": 0.3}, "body2": {"E": 1, '
     '"nu": 0.3}}}', "'materials.body1.E'"),
    ("{" + _UNITS + ', "materials": {"body1": {"E": 1, "nu": 0.3}, "body2": {"E": 1, '
     '"nu": 0.5}}}', "'materials.body2.nu'"),
    ("{" + _UNITS + ', "model": {"level": "1"}}', "'model.level'"),
    ("{" + _UNITS + ', "model": {"level": true}}', "'model.level'"),
    ("{" + _UNITS + ', "model": []}', "'model' must be an object"),
    ("{" + _UNITS + ', "contact": {"slave": 1}}', "'contact.slave'"),
    ("{" + _UNITS + ', "contact": {"penalty_factor": -1}}', "'contact.penalty_factor'"),
    ("DEEP", "nested too deeply"),
    ("HUGE", "larger than 1048576 bytes"),
    (b'{"units": {"length": "\xff"}}', "line 1: not UTF-8"),
])
def test_malformed_problem_json(tmp_path, text, key):
    """One ValueError naming problem.json and the key (before: KeyError, TypeError, or a
    message without the file), from the normal and the frictional reader alike."""
    text = {"DEEP": "[" * 100_000,  # 100 000 nested lists
            "HUGE": "{" + _UNITS + ', "pad": "' + "x" * (1 << 20) + '"}'}.get(text, text)
    for name, reader in (("tet_cubes", lambda p: read_result(p, units="mm")),
                         ("tet_cubes_friction", lambda p: read_calculix_tangential(
                             p, symmetry="whole"))):
        frd = _run(tmp_path / name, name)
        problem = frd.parent / "problem.json"
        problem.write_bytes(text if isinstance(text, bytes) else text.encode())
        with pytest.raises(ValueError, match=re.escape(key)) as exc:
            reader(frd)
        assert re.search(r"problem\.json '[^']*problem\.json'", _one_line_naming(exc, problem))


def test_problem_json_gives_units_and_frame(tmp_path):
    """A well-formed problem.json: its units and its frame are used."""
    frd = _run(tmp_path, problem=PROBLEM)
    r = read_result(frd)
    assert r.details["units"] == "mm" and r.details["level"] == 0
    np.testing.assert_array_equal(r.frame.origin, [0, 0, 1e-3])
    with pytest.raises(ValueError, match=r"units 'SI' contradict .*mm"):
        read_result(frd, units="SI")


def _through_a_pipe(data: bytes, tmp_path) -> Path:
    """A named pipe fed ``data`` by a thread (as `zcat run.frd.gz |` would)."""
    import os
    import threading

    tmp_path.mkdir(exist_ok=True)
    fifo = tmp_path / "pipe.frd"
    os.mkfifo(fifo)

    def feed():
        with open(fifo, "wb") as f:
            try:
                f.write(data)
            except BrokenPipeError:  # the reader stopped early, as it should
                pass

    threading.Thread(target=feed, daemon=True).start()
    return fifo


def test_pipe_reads_as_the_file(tmp_path):
    """A pipe has no size and cannot seek: its .frd reads as the file does, and a count it
    cannot hold is refused when it ends, having cost only what it sent."""
    data = (DATA / "two_cubes_binary.frd").read_bytes()
    a, b = read_frd(DATA / "two_cubes_binary.frd"), read_frd(_through_a_pipe(data, tmp_path))
    np.testing.assert_array_equal(a.coordinates, b.coordinates)
    for ra, rb in zip(a.results, b.results, strict=True):
        np.testing.assert_array_equal(ra.values, rb.values)
    text = _with_count(data.decode("latin-1"), "  100C", 99_999_999_999).encode("latin-1")
    reset_peak()
    before = peak_mb()
    with pytest.raises(FrdFormatError, match="binary block ends early"):
        read_frd(_through_a_pipe(text, tmp_path / "huge"))
    assert peak_mb() - before < 100


@pytest.mark.parametrize("name", ["tet_cubes", "tet_cubes_friction"])
def test_deck_of_zeros_is_not_read_whole(tmp_path, name):
    """The deck beside the .frd is read line by line, its nodes and elements skipped: 2 GB
    of zero bytes stop at the first line."""
    frd = _run(tmp_path, name)
    with open(frd.with_suffix(".inp"), "wb") as f:
        f.truncate(2 << 30)
    reset_peak()
    before = peak_mb()
    with pytest.raises(ValueError, match=r"hertz\.inp: line 1: longer than 1024") as exc:
        read_calculix(frd, units="mm") if name == "tet_cubes" else \
            read_calculix_tangential(frd, symmetry="whole")
    _one_line_naming(exc, frd.with_suffix(".inp"))
    assert peak_mb() - before < 50


# --- the audit of issue 22's fixes: decks, problem.json --------------------------------------

def _deck_with(frd: Path, old: str, new: str) -> Path:
    inp = frd.with_suffix(".inp")
    text = inp.read_text()
    assert old in text
    inp.write_text(text.replace(old, new, 1))
    return inp


def test_frd_without_an_element_block(tmp_path):
    """A .frd whose 3C block is gone (its deck beside it): was IndexError (exit 3)."""
    frd = _run(tmp_path)
    lines = frd.read_text().splitlines(keepends=True)
    start = next(i for i, line in enumerate(lines) if line.startswith("    3C"))
    end = next(i for i in range(start + 1, len(lines)) if lines[i].startswith(" -3"))
    frd.write_text("".join(lines[:start] + lines[end + 1:]))
    with pytest.raises(ValueError, match=r"holds no elements \(no 3C block\)") as exc:
        read_calculix(frd, units="mm")
    _one_line_naming(exc, frd)
    scene = tmp_path / "scene.toml"
    scene.write_text(CUBES_SCENE)
    run = _grade_command(frd, scene, tmp_path / "graded")
    assert run.returncode == 2 and run.stderr.count("\n") == 1, run.stderr
    assert str(frd) in run.stderr and "no 3C block" in run.stderr


@pytest.mark.parametrize("surface, words", [
    ("*SURFACE, NAME=SLAVE, TYPE=ELEMENT\n", r"slave surface SLAVE .*has no faces or nodes"),
    ("*SURFACE, NAME=SLAVE, TYPE=NODE\nx\ny\n", r"line 77: surface SLAVE: expected a node "
                                                r"number, got 'x'"),
    ("*SURFACE, NAME=SLAVE, TYPE=NODE\n99999999999999999999999\n",
     r"line 77: surface SLAVE: node number 99999999999999999999999 is out of range"),
    ("*SURFACE, NAME=SLAVE, TYPE=ELEMENT\n99999999999999999999, S1\n",
     r"line 77: surface SLAVE: element number 99999999999999999999 is out of range"),
    ("*SURFACE, NAME=SLAVE, TYPE=ELEMENT\n1, S1\n0, S1\n",
     r"line 78: surface SLAVE: element number 0 is out of range"),
])
def test_slave_surface_malformed(tmp_path, surface, words):
    """An empty slave surface, non-numeric node lines (were dropped silently: IndexError),
    an over-long number (OverflowError): one line naming the deck and its line."""
    frd = _run(tmp_path)
    inp = _deck_with(frd, "*SURFACE, NAME=SLAVE, TYPE=ELEMENT\n1, S1\n3, S1\n", surface)
    with pytest.raises(ValueError, match=words) as exc:
        read_calculix(frd, units="mm")
    _one_line_naming(exc, inp)


@pytest.mark.parametrize("extra, words", [
    (", 99999999999999999999999", r"line 75: \*NSET, NSET=MOVED: node number 9999"),
    (", -4", r"line 75: \*NSET, NSET=MOVED: node number -4 is out of range"),
    (", SETNAME", r"line 75: \*NSET, NSET=MOVED: expected node numbers"),
])
def test_friction_node_set_malformed(tmp_path, extra, words):
    """An over-long number in *NSET, NSET=MOVED: was OverflowError (exit 3)."""
    frd = _run(tmp_path, "tet_cubes_friction")
    text = frd.with_suffix(".inp").read_text()
    lines = text.splitlines(keepends=True)
    at = next(i for i, line in enumerate(lines) if line.startswith("*NSET, NSET=MOVED"))
    inp = _deck_with(frd, lines[at] + lines[at + 1],
                     lines[at] + lines[at + 1].rstrip("\n") + extra + "\n")
    assert f"line {at + 2}:" in words  # the data line after the keyword
    with pytest.raises(ValueError, match=words) as exc:
        read_calculix_tangential(frd, symmetry="whole")
    _one_line_naming(exc, inp)


_APPROACH = ', "materials": {"body1": {"E": 210000, "nu": 0.3}, "body2": {"E": 210000, ' \
            '"nu": 0.3}}'


@pytest.mark.parametrize("text, key", [
    # a 400-digit integer: was OverflowError (int too large to convert to float), exit 3
    ("{" + _UNITS + ', "loads": {"approach": 1' + "0" * 400 + "}}",
     r"key 'loads\.approach' must be a finite number, got 1000"),
    ("{" + _UNITS + ', "frame": {"origin": [0, 0, -1' + "0" * 400 + "]}}",
     r"key 'frame\.origin'"),
    # past Python's 4300-digit limit: was "Exceeds the limit" without the file
    ("{" + _UNITS + ',\n"loads": {"approach": 1' + "0" * 5000 + "}}",
     r"line 2: a number of 5001 digits"),
    # 5e-324 mm is 0 m: was "depth must be > 0, got 0.0" without file or key
    ("{" + _UNITS + ', "loads": {"approach": 0.01}, "model": {"far_face_depths": '
     "[5e-324, 5e-324]}" + _APPROACH + "}", r"key 'model\.far_face_depths' must be a list "
                                            r"of 2 positive numbers"),
    ("{" + _UNITS + ', "loads": {"approach": 0.01}, "model": {"far_face_depths": '
     "[1, 1e400]}" + _APPROACH + "}", r"key 'model\.far_face_depths'"),
], ids=["int-400-digits", "origin-400-digits", "int-5001-digits", "depths-subnormal",
        "depths-1e400"])
def test_problem_json_numbers_out_of_range(tmp_path, text, key):
    frd = _run(tmp_path, problem=text)
    problem = frd.parent / "problem.json"
    with pytest.raises(ValueError, match=key) as exc:
        read_result(frd, units="mm")
    assert len(_one_line_naming(exc, problem)) < 400


@pytest.mark.parametrize("name", ["tet_cubes", "tet_cubes_friction"])
def test_problem_json_settlement_not_finite(tmp_path, name):
    """Depths and E so small that the far faces' settlement (Boussinesq; Cerruti for the
    frictional reader) overflows: refused naming the keys, not an approach of Infinity or a
    ZeroDivisionError."""
    text = ("{" + _UNITS + ', "loads": {"approach": 0.01}, "model": {"far_face_depths": '
            '[1e-300, 1e-300]}, "materials": {"body1": {"E": 1e-300, "nu": 0.3}, '
            '"body2": {"E": 1e-300, "nu": 0.3}}}')
    frd = _run(tmp_path, name, problem=text)
    with pytest.raises(ValueError, match=r"'model\.far_face_depths'.*not a? ?finite") as exc:
        read_result(frd, units="mm") if name == "tet_cubes" else \
            read_calculix_tangential(frd, symmetry="whole")
    _one_line_naming(exc, frd.parent / "problem.json")


@pytest.mark.parametrize("normal", [[1e308, 1e308, 1e308], [5e-324, 5e-324, 5e-324]])
def test_problem_json_normal_of_huge_or_subnormal_components(tmp_path, normal):
    """frame.normal_into_body1 [1e308, 1e308, 1e308] said "must be a nonzero vector, got
    [0, 0, 0]" (or blamed the default x axis): it is the direction (1, 1, 1)."""
    import warnings

    problem = {"units": {"length": "mm"},
               "frame": {"origin": [0.0, 0.0, 1.0], "normal_into_body1": normal}}
    frd = _run(tmp_path, problem=problem)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = read_result(frd)
    np.testing.assert_allclose(r.frame.normal, np.full(3, 3 ** -0.5), rtol=1e-15)
    assert abs(r.frame.normal @ r.frame.x_axis) < 1e-15
