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


def main(argv):
    if len(argv) >= 3 and argv[0] == "audit":
        audit(argv[1], json.loads(argv[2]))
    elif len(argv) >= 3 and argv[0] == "tube":
        tube(argv[1], json.loads(argv[2]))
    elif len(argv) >= 3 and argv[0] == "resave":
        resave(argv[1], argv[2], argv[3:])
    else:
        fail(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
