#!/usr/bin/env python3
"""Checks dlw's DXF drawings with ezdxf, the tool designers' pipelines use.

Usage:
  dxf_check.py audit FILE EXPECT_JSON
      Reads FILE with ezdxf.readfile, runs doc.audit() and requires no errors and no fixes;
      checks $INSUNITS = 4, the five layers and their ACI colours, entity counts per layer
      (EXPECT_JSON: {"layers": {"NOTCHES": n, ...}, "notch_area_mm2": a}), that notches are
      closed LWPOLYLINEs and traces open ones, and the total notch area (shoelace) to 1e-6 mm².
  dxf_check.py tube FILE EXPECT_JSON
      Checks the TUBE layer: one closed LWPOLYLINE, the rectangle x 0..length, s seam..seam+C
      (EXPECT_JSON: {"seam": s0, "circumference": c, "length": l, "split": bool}), a LINE along
      each window edge (the seam) reaching past both ends, and a TEXT on ANNOTATION saying that
      notches cross the seam exactly when "split" is true.
  dxf_check.py crosstalk FILE EXPECT_JSON
      A robot's crosstalk computed from the drawing alone, independently of dlw's code: the
      axial segments of each sensor's U-trace (SENSOR) and leads (LEADS_PADS, XDATA kind
      "lead"), sensors told apart by the XDATA sensor number; for joint j,
      S(j) = sum of len*(y - ybar_j)/L_j over the segments' parts over [x_start_j, x_end_j],
      y = r_o*cos(s/r_o - rotation_j); crosstalk[j] = S(j) / (the same sum for the U-trace
      over its own joint). EXPECT_JSON: {"r_o": r, "joints": [{"x_start", "x_end",
      "rotation_deg", "y_bar"}], "sensors": [{"joint": j (1-based), "crosstalk": [...]}]};
      every value must agree to 1e-6.
  dxf_check.py resave FILE OUT [--move-notch DX DY] [--strip-xdata]
      Re-saves FILE with ezdxf as OUT (as a designer's tool would), optionally moving the
      first NOTCHES polyline by (DX, DY) mm and/or removing dlw's XDATA from feature entities.

Exit status 0 on success; 1 with a message on a failed check; 2 if ezdxf is missing.
"""
import json
import sys

try:
    import ezdxf
except ImportError:
    print("ezdxf is not installed for python3: run scripts/test.sh (pip install ezdxf)", file=sys.stderr)
    sys.exit(2)

LAYERS = {"NOTCHES": 30, "SENSOR": 5, "LEADS_PADS": 3, "PARTING": 1, "ANNOTATION": 7, "TUBE": 8}


def fail(msg):
    print(f"dxf_check: {msg}", file=sys.stderr)
    sys.exit(1)


def shoelace(points):
    n = len(points)
    return abs(sum(points[i][0] * points[(i + 1) % n][1] - points[(i + 1) % n][0] * points[i][1] for i in range(n))) / 2.0


def audit(path, expect):
    doc = ezdxf.readfile(path)
    auditor = doc.audit()
    if auditor.has_errors:
        fail(f"{path}: audit errors: " + "; ".join(e.message for e in auditor.errors))
    if auditor.has_fixes:
        fail(f"{path}: audit had to fix: " + "; ".join(e.message for e in auditor.fixes))
    units = doc.header.get("$INSUNITS")
    if units != 4:
        fail(f"{path}: $INSUNITS = {units}, expected 4 (mm)")
    for name, colour in LAYERS.items():
        if name not in doc.layers:
            fail(f"{path}: layer {name} missing")
        got = doc.layers.get(name).color
        if got != colour:
            fail(f"{path}: layer {name} has colour {got}, expected {colour}")
    counts = {}
    area = 0.0
    for e in doc.modelspace():
        layer = e.dxf.layer
        counts[layer] = counts.get(layer, 0) + 1
        if layer == "NOTCHES":
            if e.dxftype() != "LWPOLYLINE" or not e.closed:
                fail(f"{path}: {e.dxftype()} {e.dxf.handle} on NOTCHES is not a closed LWPOLYLINE")
            area += shoelace([(p[0], p[1]) for p in e.get_points("xy")])
        elif layer in ("SENSOR", "LEADS_PADS"):
            if e.dxftype() != "LWPOLYLINE" or e.closed:
                fail(f"{path}: {e.dxftype()} {e.dxf.handle} on {layer} is not an open LWPOLYLINE")
    if counts != expect["layers"]:
        fail(f"{path}: entities per layer {counts}, expected {expect['layers']}")
    if abs(area - expect["notch_area_mm2"]) > 1e-6:
        fail(f"{path}: notch area {area:.9f} mm², expected {expect['notch_area_mm2']:.9f} mm²")
    print(f"ok {path}: {doc.dxfversion}, layers {counts}, notch area {area:.9f} mm²")


def tube(path, expect):
    doc = ezdxf.readfile(path)
    msp = doc.modelspace()
    s0, c, length = expect["seam"], expect["circumference"], expect["length"]
    tol = 1e-9
    outlines = [e for e in msp.query("LWPOLYLINE") if e.dxf.layer == "TUBE"]
    if len(outlines) != 1 or not outlines[0].closed:
        fail(f"{path}: TUBE must hold one closed LWPOLYLINE, found {len(outlines)}")
    pts = sorted((round(p[0], 9), round(p[1], 9)) for p in outlines[0].get_points("xy"))
    want = sorted((round(x, 9), round(y, 9)) for x, y in [(0, s0), (length, s0), (length, s0 + c), (0, s0 + c)])
    if pts != want:
        fail(f"{path}: TUBE outline {pts}, expected {want}")
    area = shoelace(outlines[0].get_points("xy"))
    if abs(area - length * c) > 1e-9:
        fail(f"{path}: TUBE outline area {area}, expected L*C = {length * c}")
    seams = [e for e in msp.query("LINE") if e.dxf.layer == "TUBE"]
    for s in (s0, s0 + c):
        hit = [e for e in seams if abs(e.dxf.start.y - s) < tol and abs(e.dxf.end.y - s) < tol
               and min(e.dxf.start.x, e.dxf.end.x) < 0 and max(e.dxf.start.x, e.dxf.end.x) > length]
        if len(hit) != 1:
            fail(f"{path}: no seam LINE along s = {s} past both ends of the outline")
    texts = [e.dxf.text for e in msp.query("TEXT MTEXT") if e.dxf.layer == "ANNOTATION"]
    note = [t for t in texts if "cross the seam" in t]
    if bool(note) != expect["split"]:
        fail(f"{path}: split-notch note {'missing' if expect['split'] else 'present'}: {note}")
    labels = [e for e in msp.query("TEXT") if e.dxf.layer == "TUBE" and e.dxf.text.startswith("seam")]
    if len(labels) != 2:
        fail(f"{path}: expected 2 seam labels on TUBE, found {len(labels)}")
    print(f"ok {path}: tube {length} x {c} mm from s = {s0}, split note {bool(note)}")


def resave(path, out, args):
    doc = ezdxf.readfile(path)
    msp = doc.modelspace()
    if "--move-notch" in args:
        i = args.index("--move-notch")
        dx, dy = float(args[i + 1]), float(args[i + 2])
        notch = next(e for e in msp if e.dxf.layer == "NOTCHES")
        notch.translate(dx, dy, 0)
    if "--strip-xdata" in args:
        for e in msp:
            if e.dxf.layer != "ANNOTATION" and e.has_xdata("DLW"):
                e.discard_xdata("DLW")
    doc.saveas(out)
    print(f"ok resaved {path} as {out} ({doc.dxfversion})")


def crosstalk(path, expect):
    import math
    doc = ezdxf.readfile(path)
    r_o = expect["r_o"]
    joints = expect["joints"]
    u = {}
    leads = {}
    for e in doc.modelspace():
        if e.dxftype() != "LWPOLYLINE" or e.dxf.layer not in ("SENSOR", "LEADS_PADS"):
            continue
        xd = e.get_xdata("DLW") if e.has_xdata("DLW") else None
        if not xd:
            fail(f"{path}: a trace without DLW XDATA")
        kind, sensor = xd[0][1], xd[2][1]
        pts = [(p[0], p[1]) for p in e.get_points("xy")]
        if kind == "sensor":
            u.setdefault(sensor, []).append(pts)
        elif kind == "lead":
            leads.setdefault(sensor, []).append(pts)

    def total(lines, j):
        jt = joints[j]
        x0, x1 = jt["x_start"], jt["x_end"]
        rot = math.radians(jt["rotation_deg"])
        out = 0.0
        for pts in lines:
            for (ax, ay), (bx, by) in zip(pts, pts[1:]):
                if abs(by - ay) > 1e-9:
                    continue
                over = max(0.0, min(max(ax, bx), x1) - max(min(ax, bx), x0))
                if over > 0:
                    y = r_o * math.cos(ay / r_o - rot)
                    out += over * (y - jt["y_bar"]) / (x1 - x0)
        return out

    got = []
    for i, s in enumerate(expect["sensors"]):
        own = total(u.get(i, []), s["joint"] - 1)
        if abs(own) < 1e-12:
            fail(f"{path}: sensor {i + 1}'s U-trace reads nothing of its own joint")
        row = [(total(u.get(i, []), j) + total(leads.get(i, []), j)) / own for j in range(len(joints))]
        got.append(row)
        for j, (g, w) in enumerate(zip(row, s["crosstalk"])):
            if abs(g - w) > 1e-6:
                fail(f"{path}: sensor {i + 1} on joint {j + 1}: crosstalk {g!r} from the drawing, dlw says {w!r}")
    print(f"ok {path}: crosstalk from the drawing {got}")


def main(argv):
    if len(argv) >= 3 and argv[0] == "audit":
        audit(argv[1], json.loads(argv[2]))
    elif len(argv) >= 3 and argv[0] == "tube":
        tube(argv[1], json.loads(argv[2]))
    elif len(argv) >= 3 and argv[0] == "crosstalk":
        crosstalk(argv[1], json.loads(argv[2]))
    elif len(argv) >= 3 and argv[0] == "resave":
        resave(argv[1], argv[2], argv[3:])
    else:
        fail(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
