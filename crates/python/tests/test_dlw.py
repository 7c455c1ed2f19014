"""pytest for `import dlw`, against the `dlw` binary (DLW_BIN, default target/debug/dlw):
each Python result must be the command's result over the same inputs."""

import json
import shutil
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import dlw

ROOT = Path(__file__).resolve().parents[3]
DESIGNS = ROOT / "designs"
BIN = os.environ.get("DLW_BIN", str(ROOT / "target" / "debug" / "dlw"))


def cli(*args):
    out = subprocess.run([BIN, *map(str, args)], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return out.stdout


def cli_error(*args):
    out = subprocess.run([BIN, *map(str, args)], capture_output=True, text=True)
    assert out.returncode != 0
    return out.stderr


@pytest.fixture(scope="module")
def recordings(tmp_path_factory):
    d = tmp_path_factory.mktemp("rec")
    design = DESIGNS / "joint-d.toml"
    cli("simulate", "--design", design, "--protocol", "characterization", "--duration-s", "120", "-o", d / "char")
    cli("simulate", "--design", design, "--protocol", "random", "--duration-s", "100", "--seed", "3", "-o", d / "rand")
    return d


def test_geometry_is_inspect_json():
    design = dlw.Design.from_file(DESIGNS / "joint-a.toml")
    g = design.geometry()
    expected = json.loads(cli("inspect", DESIGNS / "joint-a.toml", "--json"))
    assert g == expected
    for key in ("y_bar_mm", "y_s_mm", "delta_y_mm", "strain_per_deg"):
        assert isinstance(g[key], float)
    assert g["delta_y_mm"] == pytest.approx(g["y_s_mm"] - g["y_bar_mm"], abs=1e-12)


def test_bad_design_raises_value_error_with_the_cli_message(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text((DESIGNS / "joint-a.toml").read_text().replace("inner_radius_mm = 0.875", "inner_radius_mm = 1.5"))
    message = cli_error("inspect", bad)
    with pytest.raises(ValueError) as e:
        dlw.Design.from_file(bad)
    first = str(e.value).splitlines()[0]
    assert first.split(": ")[-1] in message, (str(e.value), message)


def test_read_recording_gives_numpy_columns_and_the_rig(recordings):
    r = dlw.read_recording(recordings / "rand")
    text = (recordings / "rand" / "data.csv").read_text().splitlines()
    assert len(r["time_s"]) == len(text) - 1
    for key in ("time_s", "stroke_mm", "angle_deg", "v1_V"):
        assert r[key].dtype == np.float64
    assert r["rig"]["sample_hz"] == 500.0
    first = [float(x) for x in text[1].split(",")[:5]]
    assert r["v1_V"][0] == pytest.approx(first[3], abs=0)


def test_fit_matches_the_cli_and_the_estimator_matches_estimate(recordings, tmp_path):
    design = DESIGNS / "joint-d.toml"
    f = dlw.fit(recordings / "char", design, model="linear")
    cli("fit", "--design", design, recordings / "char", "--model", "linear", "-o", tmp_path / "cli.toml")
    cli_text = (tmp_path / "cli.toml").read_text()
    strip = lambda t: [l for l in t.splitlines() if not l.startswith("#")]
    assert strip(f.config_toml()) == strip(cli_text)
    s = f.summary()
    assert s["model"] == "linear" and s["sensors"][0]["gauge_factor"] > 0
    f.save(tmp_path / "py.toml")
    with pytest.raises(ValueError, match="exists"):
        f.save(tmp_path / "py.toml")
    f.save(tmp_path / "py.toml", force=True)
    # Issue 30: an input of the fit (the recording's rig.toml, the design) is never replaced,
    # even with force=True, as the command line refuses it.
    shutil.copytree(recordings / "char", tmp_path / "char")
    shutil.copy(design, tmp_path / "joint-d.toml")
    own = dlw.fit(tmp_path / "char", tmp_path / "joint-d.toml", model="linear")
    for target in (tmp_path / "char" / "rig.toml", tmp_path / "joint-d.toml", tmp_path / "char"):
        before = sorted(p.read_bytes() for p in ([target] if target.is_file() else target.iterdir()))
        with pytest.raises(ValueError, match="refused even with --force"):
            own.save(target, force=True)
        after = sorted(p.read_bytes() for p in ([target] if target.is_file() else target.iterdir()))
        assert before == after
    # The estimator over the recording equals dlw estimate's estimates.csv to 1e-9.
    cli("estimate", "--config", tmp_path / "py.toml", recordings / "rand", "-o", tmp_path / "est.csv", "--precision", "12")
    rows = (tmp_path / "est.csv").read_text().splitlines()
    col = rows[0].split(",").index("estimate_deg")
    expected = np.array([float(l.split(",")[col]) for l in rows[1:]])
    rec = dlw.read_recording(recordings / "rand")
    for est in (dlw.Estimator.from_config(tmp_path / "py.toml"), f.estimator(),
                dlw.Estimator.from_toml(f.config_toml())):
        got = est.run(rec["v1_V"])
        assert np.max(np.abs(got - expected)) < 1e-9
    # step by step, then reset, gives the same.
    est = dlw.Estimator.from_config(tmp_path / "py.toml")
    stepped = [est.step(v) for v in rec["v1_V"][:500]]
    assert np.max(np.abs(np.array(stepped) - expected[:500])) < 1e-9
    est.reset()
    assert abs(est.step(rec["v1_V"][0]) - expected[0]) < 1e-9


def test_fit_from_a_dict_and_a_pi_fit(recordings):
    rec = dlw.read_recording(recordings / "char")
    f = dlw.fit(rec, dlw.Design.from_file(DESIGNS / "joint-d.toml"), model="pi", compare=True)
    models = {m["model"]: m for m in f.summary()["sensors"][0]["models"]}
    assert set(models) == {"linear", "pi", "continuous-pi"}
    assert models["pi"]["rmse_ohm"] <= models["linear"]["rmse_ohm"] * 1.01


def test_characterize_is_the_commands_json(recordings, tmp_path):
    """characterize() returns what `dlw characterize --json` prints, but for the report path."""
    design = DESIGNS / "joint-d.toml"
    got = dlw.characterize(recordings / "char", design, kind="loops", order=4)
    want = json.loads(cli("characterize", "--design", design, recordings / "char", "--kind", "loops",
                          "--order", "4", "-o", tmp_path / "rep", "--json"))
    assert got["report"] is None and want["report"].endswith("report.html")
    got.pop("report"), want.pop("report")
    assert got == want
    with pytest.raises(ValueError, match="kind \"cubic\""):
        dlw.characterize(recordings / "char", design, kind="cubic")
    with pytest.raises(ValueError, match="--config is for --kind estimation"):
        dlw.characterize(recordings / "char", design, kind="rate", configs=[tmp_path / "x.toml"])


def test_bad_fit_input_raises_value_error(recordings):
    with pytest.raises(ValueError, match="order 1"):
        dlw.fit(recordings / "char", DESIGNS / "joint-d.toml", order=1)
    with pytest.raises(ValueError, match="unknown model"):
        dlw.fit(recordings / "char", DESIGNS / "joint-d.toml", model="cubic")
    rec = dlw.read_recording(recordings / "char")
    rec["v1_V"] = rec["v1_V"][:10]
    with pytest.raises(ValueError, match="v1_V has 10 samples"):
        dlw.fit(rec, DESIGNS / "joint-d.toml")
    rec = dlw.read_recording(recordings / "char")
    rec["v1_V"][5] = 7.5  # above the 5 V supply: the reader's own check and message
    message = None
    with pytest.raises(ValueError) as e:
        dlw.fit(rec, DESIGNS / "joint-d.toml")
    assert "v1_V" in str(e.value)


def test_unmeasured_or_late_input_is_refused_as_the_commands_refuse_it(recordings):
    """A clipped voltage and a tracker 200 ms late, from a folder or a dict: ValueError with
    the command's message, for fit, discover and characterize alike."""
    design = DESIGNS / "joint-d.toml"
    rec = dlw.read_recording(recordings / "rand")
    limit = np.percentile(rec["v1_V"], 90.0)
    rec["v1_V"] = np.minimum(rec["v1_V"], limit)
    with pytest.raises(ValueError, match="v1_V holds its largest value"):
        dlw.fit(rec, design)
    rec = dlw.read_recording(recordings / "rand")
    rows = int(round(0.2 * rec["rig"]["sample_hz"]))
    a = rec["angle_deg"]
    rec["angle_deg"] = np.concatenate([np.full(rows, a[0]), a[:-rows]])
    for call in (dlw.fit, dlw.discover, dlw.characterize):
        with pytest.raises(ValueError, match="angle is late by one delay") as e:
            call(rec, design)
        assert "the recording dict" in str(e.value)


def test_simulate_equals_the_cli(tmp_path):
    r = dlw.simulate(DESIGNS / "joint-a.toml", protocol="random", duration_s=5.0, seed=4)
    cli("simulate", "--design", DESIGNS / "joint-a.toml", "--protocol", "random", "--duration-s", "5", "--seed", "4", "-o", tmp_path / "s")
    c = dlw.read_recording(tmp_path / "s")
    # data.csv holds 6 decimals (4 for the angle): equal to its rounding.
    for key, half_ulp in (("time_s", 5e-7), ("stroke_mm", 5e-7), ("angle_deg", 5e-5), ("v1_V", 5e-7)):
        assert np.max(np.abs(r[key] - c[key])) <= half_ulp * 1.0001, key
    with pytest.raises(ValueError, match="unknown protocol"):
        dlw.simulate(DESIGNS / "joint-a.toml", protocol="sideways")


def test_discover_equals_the_cli_json(recordings, tmp_path):
    design = DESIGNS / "joint-d.toml"
    out = json.loads(cli("discover", "--design", design, recordings / "rand", "-o", tmp_path / "d", "--json"))
    got = dlw.discover(recordings / "rand", design)
    scenario = got.pop("scenario_toml")
    assert scenario == (tmp_path / "d" / "scenario.toml").read_text()
    out.pop("scenario")
    out.pop("report")
    assert got == out
