"""pytest for the robot runtime from Python (`dlw.RobotEstimator`, `dlw.tip`, `dlw.backbone`,
`dlw.Robot`): each result must be the Rust runtime's over the same inputs, to 1e-9. The Rust
outputs are crates/estimator/tests/data/robot-runtime.json, which the Rust test robot_golden
checks is what the runtime computes today; `dlw.Robot` is compared with the `dlw` binary
(DLW_BIN, default target/debug/dlw): `inspect --json`, `estimator-config` and `estimate`."""

import csv
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import dlw

ROOT = Path(__file__).resolve().parents[3]
GOLDEN = json.loads((ROOT / "crates/estimator/tests/data/robot-runtime.json").read_text())
TOLERANCE = 1e-9
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


def columns(path, names):
    """Columns `names` of a CSV file, as float arrays."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in names}


@pytest.fixture(scope="module")
def estimator():
    return dlw.RobotEstimator.from_toml(GOLDEN["config_toml"])


def test_run_matches_the_rust_runtime(estimator):
    volts = np.array(GOLDEN["volts"])
    assert (estimator.joints, estimator.sensors) == (3, 4)
    angles, flags = estimator.run(volts, flags=True)
    assert angles.shape == (len(volts), 3) and flags.shape == angles.shape
    assert np.max(np.abs(angles - np.array(GOLDEN["angles_deg"]))) <= TOLERANCE
    assert (flags == np.array(GOLDEN["flags"])).all()
    assert np.abs(angles).max() > 10.0, "the robot bends"
    # run starts from a fresh estimator and leaves this one untouched.
    again = estimator.run(volts)
    assert np.array_equal(again, angles)


def test_step_matches_run(estimator):
    volts = GOLDEN["volts"]
    estimator.reset()
    for k in range(40):
        angles = estimator.step(volts[k])
        assert np.max(np.abs(np.array(angles) - GOLDEN["angles_deg"][k])) <= TOLERANCE
        assert estimator.flags == GOLDEN["flags"][k]
    estimator.reset()
    assert estimator.flags == [0, 0, 0]


def test_tip_and_backbone_match_the_rust_runtime(estimator):
    angles = np.array(GOLDEN["angles_deg"])
    pose = dlw.tip(angles, estimator)
    assert pose["position_mm"].shape == (len(angles), 3)
    assert pose["rotation"].shape == (len(angles), 3, 3)
    assert pose["quaternion"].shape == (len(angles), 4)
    for key, golden in [("position_mm", "tip_position_mm"), ("rotation", "tip_rotation"), ("quaternion", "tip_quaternion")]:
        assert np.max(np.abs(pose[key] - np.array(GOLDEN[golden]))) <= TOLERANCE, key
    points = dlw.backbone(angles, estimator, points=GOLDEN["backbone_points"])
    assert points.shape == (len(angles), GOLDEN["backbone_points"], 3)
    assert np.max(np.abs(points - np.array(GOLDEN["backbone_mm"]))) <= TOLERANCE
    # One row of angles gives one pose, without the leading axis; the tip is the last point.
    one = dlw.tip(angles[7], estimator)
    assert one["position_mm"].shape == (3,)
    assert np.allclose(one["position_mm"], points[7, -1], atol=1e-12, rtol=0)
    assert dlw.backbone(list(angles[7]), estimator, points=5).shape == (5, 3)


def test_configs_from_a_dict_and_a_file(estimator, tmp_path):
    config = estimator.config()
    assert config["joint"][1]["rotation_deg"] == 90.0
    from_dict = dlw.RobotEstimator.from_dict(config)
    volts = np.array(GOLDEN["volts"][:20])
    assert np.array_equal(from_dict.run(volts), estimator.run(volts))
    path = tmp_path / "robot.toml"
    path.write_text(estimator.config_toml())
    from_file = dlw.RobotEstimator.from_config(path)
    assert np.array_equal(from_file.run(volts), estimator.run(volts))
    # dlw.tip takes the config as a dict or a file too.
    angles = np.array(GOLDEN["angles_deg"][:5])
    assert np.array_equal(dlw.tip(angles, config)["position_mm"], dlw.tip(angles, path)["position_mm"])
    straight = dlw.tip([0.0, 0.0, 0.0], config)
    assert np.allclose(straight["position_mm"], [0.0, 0.0, config["joint"][2]["x_end_mm"]], atol=1e-12)


def test_bad_input_raises_value_error_naming_it(estimator, tmp_path):
    with pytest.raises(ValueError, match="volts has 3 columns, must have 4"):
        estimator.run(np.zeros((5, 3)))
    with pytest.raises(ValueError, match="3 voltages were given, the robot has 4 sensors"):
        estimator.step([2.5, 2.5, 2.5])
    with pytest.raises(ValueError, match=r"angles\[1, 2\] = NaN is not a finite number"):
        dlw.tip(np.array([[0.0, 0.0, 0.0], [0.0, 0.0, np.nan]]), estimator)
    with pytest.raises(ValueError, match="angles has 2 columns, must have 3"):
        dlw.backbone(np.zeros((4, 2)), estimator)
    config = estimator.config()
    config["sensor"][3]["crosstalk"][2] = 0.5
    with pytest.raises(ValueError, match=r"sensor 4: crosstalk\[3\] = 0.5 is its own joint's and must be 1"):
        dlw.RobotEstimator.from_dict(config)
    bad = tmp_path / "bad.toml"
    bad.write_text("joint = 3\n")
    with pytest.raises(ValueError, match="bad.toml"):
        dlw.RobotEstimator.from_config(bad)


@pytest.mark.parametrize("name", ["robot-bdb.toml", "robot-bc.toml"])
def test_robot_inspect_is_the_cli_json(name):
    path = DESIGNS / name
    robot = dlw.Robot.from_file(path)
    expected = json.loads(cli("inspect", path, "--json"))
    assert robot.inspect() == expected
    assert (robot.name, robot.joints, robot.sensors) == (
        expected["name"], len(expected["joints"]), len(expected["sensors"]))
    assert any(c != 0.0 for s in expected["sensors"] for j, c in enumerate(s["crosstalk"]) if j + 1 != s["joint"])


@pytest.fixture(scope="module")
def bdb_run(tmp_path_factory):
    """A simulated robot-bdb recording, the config `dlw estimator-config` writes for it and
    `dlw estimate`'s estimates, at 15 decimals."""
    d = tmp_path_factory.mktemp("bdb")
    robot = DESIGNS / "robot-bdb.toml"
    cli("simulate", "--design", robot, "--protocol", "random", "--seed", "2", "--duration-s", "20", "-o", d / "rec")
    cli("estimator-config", robot, "--gauge-factor", "15.3", "--r0-ohm", "215e3", "-o", d / "cfg.toml")
    cli("estimate", "--config", d / "cfg.toml", d / "rec", "-o", d / "est.csv", "--precision", "15")
    return d


def test_robot_estimator_and_tip_equal_dlw_estimate(bdb_run):
    robot = dlw.Robot.from_file(DESIGNS / "robot-bdb.toml")
    v = [f"v{i}_V" for i in range(1, robot.sensors + 1)]
    a = [f"angle{k}_est_deg" for k in range(1, robot.joints + 1)]
    rec = columns(bdb_run / "rec" / "data.csv", v)
    est = columns(bdb_run / "est.csv", a + ["tip_x_mm", "tip_y_mm", "tip_z_mm"])
    volts = np.column_stack([rec[k] for k in v])
    angles = robot.estimator(bdb_run / "cfg.toml").run(volts)
    expected_angles = np.column_stack([est[k] for k in a])
    assert np.max(np.abs(angles - expected_angles)) <= TOLERANCE
    assert np.abs(angles).max() > 5.0, "the robot bends"
    expected_tip = np.column_stack([est["tip_x_mm"], est["tip_y_mm"], est["tip_z_mm"]])
    pose = robot.tip(angles)
    assert pose["position_mm"].shape == (len(angles), 3)
    assert np.max(np.abs(pose["position_mm"] - expected_tip)) <= TOLERANCE
    # The tip moves: a straight robot's tip would pass a comparison of constants.
    assert np.ptp(expected_tip, axis=0).max() > 1.0
    # One row of angles, as a list, gives that row's pose.
    one = robot.tip(list(angles[100]))
    assert np.max(np.abs(one["position_mm"] - expected_tip[100])) <= TOLERANCE
    # The backbone ends at the tip; the module's tip with the config file agrees.
    points = robot.backbone(angles[:50], points=7)
    assert points.shape == (50, 7, 3)
    assert np.max(np.abs(points[:, -1] - expected_tip[:50])) <= TOLERANCE
    assert np.array_equal(dlw.tip(angles[:50], bdb_run / "cfg.toml")["position_mm"], pose["position_mm"][:50])


def test_robot_estimator_config_is_the_cli_config(bdb_run):
    robot = dlw.Robot.from_file(DESIGNS / "robot-bdb.toml")
    config = robot.estimator_config(gauge_factor=15.3, r0_ohm=215e3)
    assert config == dlw.RobotEstimator.from_config(bdb_run / "cfg.toml").config()
    # One value per sensor, and the estimator takes the dict and the TOML text.
    per_sensor = robot.estimator_config(gauge_factor=[15.3, 15.3, 15.3], r0_ohm=215e3, divider_ohm=[99.6e3] * 3)
    assert per_sensor == config
    text = (bdb_run / "cfg.toml").read_text()
    assert robot.estimator(text).config() == robot.estimator(config).config() == config
    with pytest.raises(ValueError, match="--gauge-factor is given 2 times; the robot has 3 sensors"):
        robot.estimator_config(gauge_factor=[15.3, 15.0], r0_ohm=215e3)
    message = cli_error("estimator-config", DESIGNS / "robot-bdb.toml", "--gauge-factor", "15.3", "--r0-ohm=-1", "-o", bdb_run / "bad.toml")
    with pytest.raises(ValueError) as e:
        robot.estimator_config(gauge_factor=15.3, r0_ohm=-1.0)
    assert str(e.value) in message


def test_robot_refuses_another_robots_config(bdb_run):
    bdb = dlw.Robot.from_file(DESIGNS / "robot-bdb.toml")
    bc = dlw.Robot.from_file(DESIGNS / "robot-bc.toml")
    bc_config = bc.estimator_config(gauge_factor=15.3, r0_ohm=215e3)
    assert bc.estimator(bc_config).joints == 2
    with pytest.raises(ValueError, match=r'the config has 2 joints and 3 sensors, the robot "Robot BDB" has 3 joints and 3 sensors'):
        bdb.estimator(bc_config)
    with pytest.raises(ValueError, match=r'the config has 3 joints and 3 sensors, the robot "Robot BC" has 2 joints and 3 sensors'):
        bc.estimator(bdb_run / "cfg.toml")
    # Same counts, another robot: joint 2 turned elsewhere, or with 9 notches.
    config = bdb.estimator_config(gauge_factor=15.3, r0_ohm=215e3)
    turned = json.loads(json.dumps(config))
    turned["joint"][1]["rotation_deg"] = 90.0
    with pytest.raises(ValueError, match=r'joint 2: the config\'s rotation_deg = 90 and the robot "Robot BDB"\'s 120'):
        bdb.estimator(turned)
    other = json.loads(json.dumps(config))
    other["joint"][1]["geometry"]["notch_count"] = 9
    with pytest.raises(ValueError, match=r"joint 2: the config's geometry is not the robot \"Robot BDB\"'s design"):
        bdb.estimator(other)


def test_robot_bad_input_raises_the_commands_message(tmp_path):
    missing = tmp_path / "robot.toml"
    missing.write_text('name = "R"\n[[joint]]\ndesign = "no-such-joint.toml"\nrotation_deg = 0.0\n')
    message = cli_error("inspect", missing, "--json")
    with pytest.raises(ValueError) as e:
        dlw.Robot.from_file(missing)
    assert "no-such-joint.toml" in str(e.value)
    assert message.strip() == "dlw: error: " + str(e.value)
    robot = dlw.Robot.from_file(DESIGNS / "robot-bdb.toml")
    with pytest.raises(ValueError, match="angles has 2 columns, must have 3"):
        robot.tip(np.zeros((4, 2)))
    with pytest.raises(ValueError, match=r"angles\[0, 1\] = inf is not a finite number"):
        robot.backbone([[0.0, np.inf, 0.0]])
