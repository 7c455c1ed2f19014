"""A robot bench for `tests/import_robot.rs`, written independently of dlw's own generators
(numpy only, quaternions composed by hand): a three-joint robot whose joints bend about their
own axes, each turned by its rotation_deg about the tube's z (docs/robots.md, "Base frame and
kinematics": a positive angle bends toward -y_j, i.e. a right-handed turn about x_j =
R_z(rotation_j)·x), seen by one 6-DOF tracker tool per joint just distal of it (tool of joint
1 at the tip) and a reference tool on the base, all in an NDI Track log (CSV, NDI's columns,
`Port:N` handles, `Missing` frames). The tracker's clock starts 0.437 s after the DAQ's and
runs 250 ppm fast; every tool's orientation carries an independent random turn of
NOISE_DEG RMS per axis; joint 2's tool is lost for a burst of frames.

Writes into OUT: daq.csv (time_s, AI0..AI2 sensor voltages, S1..S3 stroke voltages),
aurora.csv, truth.csv (time_s, angle1_deg..angle3_deg: the true joint angles at the DAQ's
rows). The log's tools are in the order LOG_ORDER (not the joints' order) so that the
import's tool mapping is exercised.

With SWAY_DEG > 0 the base (and the reference tool on it) sways by up to that angle about an
axis across the tube after the still start, so only a reference tool gives the proximal joint's
angle. Joint 1's tool is 5-DOF: its roll about its axis is random every frame (no other tool's
angle is taken in its frame).

Usage: python3 robot_bench.py OUT [SEED] [SWAY_DEG]
"""

import sys

import numpy as np

DAQ_HZ = 200.0
TRACKER_HZ = 40.0
DURATION_S = 60.0
STILL_S = 5.0
OFFSET_S = 0.437
DRIFT_PPM = 250.0
NOISE_DEG = 0.05
LAG_S = 0.03
GAIN_DEG_PER_MM = 33.0
MM_PER_V = 0.5
ROTATION_DEG = [0.0, 120.0, 240.0]
# Per joint: amplitude (deg) and two frequencies (Hz) with a phase.
PATTERNS = [(25.0, 0.11, 0.23, 0.3), (30.0, 0.07, 0.31, 1.1), (20.0, 0.13, 0.19, 2.0)]
CROSSTALK = np.array([[1.0, 0.0, -0.005], [0.0, 1.0, -0.005], [0.0, 0.0, 1.0]])
STRAIN_PER_DEG = 1e-4
GF, R0, DIVIDER, SUPPLY = 15.0, 215e3, 99.6e3, 5.0
# The log's tool blocks: (what, port). Joint k's tool is "joint k"; the base's "reference".
LOG_ORDER = [("reference", 1), ("joint 3", 2), ("joint 1", 3), ("joint 2", 4)]
# Joint 2's tool is lost for this many frames from this frame on.
LOST_FROM, LOST_FRAMES = 1200, 8


def angles_deg(t):
    """The true joint angles (deg) at times t (s): still, then a smooth onset."""
    t = np.asarray(t, dtype=float)
    onset = np.clip((t - STILL_S) / 3.0, 0.0, 1.0)
    onset = onset * onset * (3.0 - 2.0 * onset)
    out = []
    for amp, f1, f2, phase in PATTERNS:
        s = t - STILL_S
        wave = np.sin(2 * np.pi * f1 * s + phase) - np.sin(phase) + 0.5 * np.sin(2 * np.pi * f2 * s)
        out.append(amp * onset * wave / 1.5)
    return np.array(out)


def quat(axis, angle):
    axis = np.asarray(axis, dtype=float)
    axis = axis / np.linalg.norm(axis)
    return np.concatenate([[np.cos(angle / 2)], np.sin(angle / 2) * axis])


def mul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array(
        [
            w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
            w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
        ]
    )


def noisy(q, rng):
    v = np.radians(NOISE_DEG) * rng.standard_normal(3)
    n = np.linalg.norm(v)
    return mul(q, quat(v, n)) if n > 0 else q


def tool_orientations(theta_deg, mount):
    """Each joint's tool orientation (joint 1 first) for one frame's angles: the base's mount,
    then joint N (proximal) to joint k, each a turn about its own x_j in the frame it sits in."""
    n = len(theta_deg)
    tools = [None] * n
    q = mount
    for j in reversed(range(n)):
        rot = np.radians(ROTATION_DEG[j])
        axis = [np.cos(rot), np.sin(rot), 0.0]  # R_z(rotation)·x
        q = mul(q, quat(axis, np.radians(theta_deg[j])))
        tools[j] = q
    return tools


def main():
    out = sys.argv[1]
    rng = np.random.default_rng(int(sys.argv[2]) if len(sys.argv) > 2 else 7)
    sway_deg = float(sys.argv[3]) if len(sys.argv) > 3 else 0.0
    # DAQ.
    t = np.arange(int(DURATION_S * DAQ_HZ)) / DAQ_HZ
    theta = angles_deg(t)
    mixed = CROSSTALK @ theta
    r = R0 * (1.0 + GF * STRAIN_PER_DEG * mixed)
    volts = SUPPLY * r / (r + DIVIDER) + 5e-4 * rng.standard_normal(mixed.shape)
    strokes = angles_deg(t - LAG_S) / GAIN_DEG_PER_MM / MM_PER_V
    with open(f"{out}/daq.csv", "w") as f:
        f.write("time_s,AI0,AI1,AI2,S1,S2,S3\n")
        for i in range(len(t)):
            row = [f"{t[i]:.6f}"] + [f"{v:.6f}" for v in volts[:, i]] + [f"{s:.6f}" for s in strokes[:, i]]
            f.write(",".join(row) + "\n")
    with open(f"{out}/truth.csv", "w") as f:
        f.write("time_s,angle1_deg,angle2_deg,angle3_deg\n")
        for i in range(len(t)):
            f.write(f"{t[i]:.6f}," + ",".join(f"{a:.6f}" for a in theta[:, i]) + "\n")
    # Tracker.
    mount = mul(quat([0.6, 0.0, 0.8], 0.7), quat([0.0, 1.0, 0.0], 0.4))
    block = "PortHandle,Face#,TransformStatus,Q0,Qx,Qy,Qz,Tx,Ty,Tz,Error"
    header = "#Tools,ToolInfo,Frame#," + block + "".join(",#Markers," + block for _ in LOG_ORDER[1:])
    lines = [header]
    frames = int((DURATION_S - OFFSET_S - 1.0) * TRACKER_HZ)
    for k in range(frames):
        tau = k / TRACKER_HZ
        td = OFFSET_S + tau * (1.0 + DRIFT_PPM * 1e-6)
        onset = np.clip((td - STILL_S) / 3.0, 0.0, 1.0)
        sway = np.radians(sway_deg) * onset * np.sin(2 * np.pi * (td - STILL_S) / 23.0)
        base = mul(mount, quat([0.0, 1.0, 0.0], sway))  # about the base's own y, across the tube
        tools = tool_orientations(angles_deg([td])[:, 0], base)
        # A 5-DOF sensor has no roll: what the log holds about its z is arbitrary.
        tools[0] = mul(tools[0], quat([0.0, 0.0, 1.0], 2 * np.pi * rng.uniform()))
        cells = [f"{len(LOG_ORDER)}", "Aurora", f"{1000 + k}"]
        for i, (what, port) in enumerate(LOG_ORDER):
            if i > 0:
                cells.append("3")
            q = base if what == "reference" else tools[int(what.split()[1]) - 1]
            q = noisy(q, rng)
            if what == "joint 2" and LOST_FROM <= k < LOST_FROM + LOST_FRAMES:
                cells += [f"Port:{port}", "0", "Missing"] + [""] * 8
            else:
                cells += [f"Port:{port}", "0", "OK"] + [f"{c:.7f}" for c in q] + ["10.0", "20.0", "30.0", "0.12"]
        lines.append(",".join(cells))
    with open(f"{out}/aurora.csv", "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
