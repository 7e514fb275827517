"""Mesh series (issue 25 item 4): observed orders and Richardson extrapolation against
synthetic series of known order, err = e_inf + C h^p, and ``grade --series`` end to end
on sampled Hertz pressures whose peak and radius carry an error C h^2."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from fem_extra import require
from scene_files import ball_on_plane

require("matplotlib")

from fem_validation.grading.series import observed_order, richardson  # noqa: E402


@pytest.mark.parametrize("p", [1.0, 2.0, 2.5])
@pytest.mark.parametrize("h", [[0.4, 0.2, 0.1], [0.3, 0.17, 0.1], [1e-4, 6e-5, 2.5e-5, 1e-5]])
def test_known_order_recovered(p, h):
    e_inf, c = 0.003, -0.08 / max(h) ** p  # an error of 8% on the coarsest mesh
    values = [e_inf + c * x ** p for x in h]
    r = richardson(h, values)
    assert r.behaviour == "monotone"
    assert r.order == pytest.approx(p, rel=1e-9)
    assert r.extrapolated == pytest.approx(e_inf, abs=1e-12 + 1e-9 * abs(c))
    # the uncertainty is 1.25 times the distance of the finest value to the limit
    assert r.uncertainty == pytest.approx(1.25 * abs(values[np.argmin(h)] - e_inf), rel=1e-6)
    assert all(o == pytest.approx(p, rel=1e-9) for o in r.orders)


def test_wrong_order_is_seen():
    """A first-order series is not reported as second order, and a series that is first
    order on the coarse meshes and second on the fine ones reports the fine meshes'."""
    h = [0.4, 0.2, 0.1]
    assert abs(richardson(h, [x for x in h]).order - 2.0) > 0.9
    # a 2% error in one value moves the order visibly
    exact = [x ** 2 for x in h]
    off = [exact[0], exact[1] * 1.02, exact[2]]
    assert abs(richardson(h, off).order - 2.0) > 0.03  # measured 0.048
    mixed = richardson([0.8, 0.4, 0.2, 0.1], [0.5, 0.16, 0.04, 0.01])
    assert mixed.order == pytest.approx(2.0) and mixed.orders[0] == pytest.approx(
        math.log2(0.34 / 0.12))


def test_behaviours():
    h = [0.4, 0.2, 0.1]
    assert observed_order(h, [0.1, -0.05, 0.02]) == (pytest.approx(math.nan, nan_ok=True),
                                                     "oscillating")
    assert observed_order(h, [0.01, 0.02, 0.04])[1] == "diverging"
    assert observed_order(h, [0.01, 0.01, 0.01])[1] == "converged"
    assert observed_order(h, [0.01, math.nan, 0.01])[1] == "not available"
    r = richardson(h[:2], [0.1, 0.05])
    assert r.behaviour == "too few meshes" and math.isnan(r.order)


@pytest.mark.parametrize("h, values, message", [
    ([0.1, 0.1, 0.2], [1, 2, 3], "two meshes of the same size"),
    ([0.1, -0.2, 0.3], [1, 2, 3], "mesh sizes must be finite numbers > 0"),
    ([0.1, 0.2], [1, 2, 3], "the same length"),
])
def test_bad_series(h, values, message):
    with pytest.raises(ValueError, match=message):
        richardson(h, values)


# --- the command --------------------------------------------------------------------------

SCENE = ball_on_plane("ball R 10 mm on a plane", 1000.0)
K = 40.0  # the synthetic error's constant: a and p0 off by K (h/a)^2 ... [-]


def _run(path: Path, spacing: float) -> Path:
    """Hertz's pressure (closed form, 1000 N) on a grid of ``spacing`` a, its radius and peak
    both scaled by 1 + K s^2 (s = spacing / a): a second-order error, with the force line
    Hertz's load so that Hertz is evaluated where the exact field was."""
    e_star = 210e9 / (2 * (1 - 0.09))
    a = (3 * 1000.0 * 0.01 / (4 * e_star)) ** (1 / 3)
    p0 = 3 * 1000.0 / (2 * math.pi * a * a)
    err = 1 + K * spacing ** 2 * 1e-2
    n = int(round(1.4 / spacing))
    x = np.arange(-n, n + 1) * spacing * a
    gx, gy = np.meshgrid(x, x)
    p = p0 * err * np.sqrt(np.clip(1 - (gx ** 2 + gy ** 2) / (a * err) ** 2, 0, None))
    rows = "\n".join(f"{u:.10e},{v:.10e},{w:.10e}"
                     for u, v, w in zip(gx.ravel(), gy.ravel(), p.ravel(), strict=True))
    path.write_text("# force = 1000\nx,y,p\n" + rows + "\n")
    return path


def test_grade_series_command(tmp_path, capsys):
    import json

    from fem_validation.cli.grade import main

    (tmp_path / "s.toml").write_text(SCENE)
    runs = [_run(tmp_path / f"run{k}.csv", s) for k, s in enumerate((0.2, 0.1, 0.05))]
    code = main(["--series", *map(str, runs[::-1]), "--scene", str(tmp_path / "s.toml"),
                 "--expected-order", "2", "--out", str(tmp_path / "g")])
    out = capsys.readouterr()
    assert code in (0, 1), out.err
    g = json.loads((tmp_path / "g" / "grade.json").read_text())
    assert g["kind"] == "mesh series" and len(g["grades"]) == 3
    assert g["h"] == sorted(g["h"], reverse=True)  # coarse to fine, whatever the order given
    # the mesh size is the grid spacing (interior nodes carry spacing^2 each)
    a = g["grades"][0]["hertz"]["a"]
    np.testing.assert_allclose(np.array(g["h"]) / a, [0.2, 0.1, 0.05], rtol=1e-6)
    p0 = g["metrics"]["p0_rel_err"]
    # the p^2 fit of the scaled field: p0 off by exactly K s^2 / 100, order 2, limit 0
    assert p0["order"] == pytest.approx(2.0, abs=0.01)
    assert abs(p0["extrapolated"]) < 2e-4
    assert g["metrics"]["a_fit_rel_err"]["order"] == pytest.approx(2.0, abs=0.01)
    md = (tmp_path / "g" / "grade.md").read_text()
    assert "| p0 (fit) |" in md and "Expected order: 2" in md
    assert (tmp_path / "g" / "grade.png").stat().st_size > 1000


@pytest.mark.parametrize("extra, message", [
    (["--force", "10"], "--force do(es) not apply to --series"),
    (["--expected-order", "2"], None),
])
def test_series_bad_options(tmp_path, capsys, extra, message):
    from fem_validation.cli.grade import main

    (tmp_path / "s.toml").write_text(SCENE)
    run = _run(tmp_path / "one.csv", 0.2)
    if message is None:  # --expected-order without --series
        code = main([str(run), "--scene", str(tmp_path / "s.toml"), *extra,
                     "--out", str(tmp_path / "g")])
        message = "--expected-order only applies to --series"
    else:
        code = main(["--series", str(run), str(_run(tmp_path / "two.csv", 0.1)),
                     "--scene", str(tmp_path / "s.toml"), *extra, "--out", str(tmp_path / "g")])
    err = capsys.readouterr().err
    assert code == 2 and message in err and len(err.strip().splitlines()) == 1, err
    code = main(["--series", str(run), "--scene", str(tmp_path / "s.toml"),
                 "--out", str(tmp_path / "g3")])
    err = capsys.readouterr().err
    assert code == 2 and "at least 2 results" in err
    code = main(["--series", str(run), str(run), "--scene", str(tmp_path / "s.toml"),
                 "--out", str(tmp_path / "g4")])
    err = capsys.readouterr().err
    assert code == 2 and "names a result twice" in err
