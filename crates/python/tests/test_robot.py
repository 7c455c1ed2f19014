"""pytest for the robot runtime from Python (`dlw.RobotEstimator`, `dlw.tip`, `dlw.backbone`):
each result must be the Rust runtime's over the same inputs, to 1e-9. The Rust outputs are
crates/estimator/tests/data/robot-runtime.json, which the Rust test robot_golden checks is what
the runtime computes today."""

import json
from pathlib import Path

import numpy as np
import pytest

import dlw

ROOT = Path(__file__).resolve().parents[3]
GOLDEN = json.loads((ROOT / "crates/estimator/tests/data/robot-runtime.json").read_text())
TOLERANCE = 1e-9


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
