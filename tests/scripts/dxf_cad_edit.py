#!/usr/bin/env python3
"""Edits a dlw drawing with ezdxf the way designers' CAD tools change it (tests/dxf_cad_import.rs).

Usage: dxf_cad_edit.py IN OUT EDIT [ARGS...]
  r12                    save as AutoCAD R12 (ezdxf's r12export: POLYLINEs, no $INSUNITS)
  resave VERSION         re-save as VERSION (R2000, R2018)
  importer VERSION       rebuild in a new VERSION document with ezdxf's Importer (drops XDATA)
  lines                  redraw every NOTCHES polyline as LINEs (exploded), in reverse order
  explode                explode every polyline on NOTCHES, SENSOR, LEADS_PADS and PARTING
                         into LINEs (ezdxf's explode(), as CAD's EXPLODE does)
  arc-edge SAGITTA       redraw the first notch as three LINEs and an ARC bulging SAGITTA mm
                         towards the free end in place of its distal edge (x = x_min)
  gap GAP                redraw the first notch as LINEs, its last LINE GAP mm short
  extras                 add a title block (LWPOLYLINE and TEXT on TITLE), a CIRCLE on layer 0
                         and a LINE on dlw's TUBE layer
  move INDEX DX DY       move the NOTCHES entity number INDEX (file order) by (DX, DY) mm
  delete INDEX           delete the NOTCHES entity number INDEX
  inches                 scale everything by 1/25.4 and set $INSUNITS = 1 (inches)
  sha256                 print the SHA-256 of IN (OUT is ignored)
Edits can be chained: EDIT ARGS... + EDIT ARGS...

Exit status 0 on success; 1 with a message on a failed edit; 2 if ezdxf is missing.
"""
import hashlib
import math
import sys

try:
    import ezdxf
    from ezdxf.addons import Importer, r12export
    from ezdxf.math import Matrix44
except ImportError:
    print("ezdxf is not installed for python3: run scripts/test.sh (pip install ezdxf)", file=sys.stderr)
    sys.exit(2)

VERSIONS = {"R12": "AC1009", "R2000": "AC1015", "R2018": "AC1032"}


def fail(msg):
    print(f"dxf_cad_edit: {msg}", file=sys.stderr)
    sys.exit(1)


def notches(doc):
    return [e for e in doc.modelspace() if e.dxf.layer == "NOTCHES"]


def corners(e):
    return [(p[0], p[1]) for p in e.get_points("xy")]


def as_lines(doc, e):
    msp = doc.modelspace()
    pts = corners(e)
    lines = []
    for i in range(len(pts)):
        a, b = pts[i], pts[(i + 1) % len(pts)]
        lines.append(msp.add_line(a, b, dxfattribs={"layer": "NOTCHES"}))
    msp.delete_entity(e)
    return lines


def edit(doc, name, args):
    msp = doc.modelspace()
    if name == "resave":
        doc.dxfversion = VERSIONS[args[0]]
    elif name == "lines":
        for e in reversed(notches(doc)):
            as_lines(doc, e)
    elif name == "explode":
        for e in list(msp):
            if e.dxftype() in ("LWPOLYLINE", "POLYLINE") and e.dxf.layer in ("NOTCHES", "SENSOR", "LEADS_PADS", "PARTING"):
                e.explode()
    elif name == "arc-edge":
        sag = float(args[0])
        e = notches(doc)[0]
        pts = corners(e)
        x0 = min(p[0] for p in pts)
        x1 = max(p[0] for p in pts)
        s0 = min(p[1] for p in pts)
        s1 = max(p[1] for p in pts)
        msp.delete_entity(e)
        a = {"layer": "NOTCHES"}
        msp.add_line((x0, s1), (x1, s1), dxfattribs=a)
        msp.add_line((x1, s1), (x1, s0), dxfattribs=a)
        msp.add_line((x1, s0), (x0, s0), dxfattribs=a)
        half = (s1 - s0) / 2.0
        r = (half * half + sag * sag) / (2.0 * sag)
        cx, cy = x0 - sag + r, (s0 + s1) / 2.0
        alpha = math.degrees(math.asin(half / r))
        msp.add_arc((cx, cy), r, 180.0 - alpha, 180.0 + alpha, dxfattribs=a)
    elif name == "gap":
        gap = float(args[0])
        lines = as_lines(doc, notches(doc)[0])
        last = lines[-1]
        s, t = last.dxf.start, last.dxf.end
        d = math.dist((s[0], s[1]), (t[0], t[1]))
        k = (d - gap) / d
        last.dxf.end = (s[0] + (t[0] - s[0]) * k, s[1] + (t[1] - s[1]) * k)
    elif name == "extras":
        doc.layers.add("TITLE")
        if "TUBE" not in doc.layers:
            doc.layers.add("TUBE")
        msp.add_lwpolyline([(0, -10), (40, -10), (40, -4), (0, -4)], close=True, dxfattribs={"layer": "TITLE"})
        msp.add_text("Title block: joint drawing, rev B", dxfattribs={"layer": "TITLE", "height": 1.0, "insert": (1, -8)})
        msp.add_circle((20, 20), 2.0, dxfattribs={"layer": "0"})
        msp.add_line((0, -3), (14, -3), dxfattribs={"layer": "TUBE"})
    elif name == "move":
        e = notches(doc)[int(args[0])]
        e.translate(float(args[1]), float(args[2]), 0)
    elif name == "delete":
        msp.delete_entity(notches(doc)[int(args[0])])
    elif name == "inches":
        m = Matrix44.scale(1 / 25.4, 1 / 25.4, 1 / 25.4)
        for e in msp:
            e.transform(m)
        doc.header["$INSUNITS"] = 1
    else:
        fail(f"unknown edit {name!r}\n{__doc__}")
    return doc


def main(argv):
    if len(argv) < 3:
        fail(__doc__)
    src, out, rest = argv[0], argv[1], argv[2:]
    if rest[0] == "sha256":
        with open(src, "rb") as f:
            print(hashlib.sha256(f.read()).hexdigest())
        return
    doc = ezdxf.readfile(src)
    steps = []
    for word in rest:
        if word == "+" or not steps:
            steps.append([])
        if word != "+":
            steps[-1].append(word)
    finish = None
    for step in steps:
        name, args = step[0], step[1:]
        if name == "r12":
            finish = ("r12", None)
        elif name == "importer":
            target = ezdxf.new(args[0])
            target.units = doc.units
            imp = Importer(doc, target)
            imp.import_tables()
            imp.import_modelspace()
            imp.finalize()
            doc = target
        else:
            doc = edit(doc, name, args)
    if finish and finish[0] == "r12":
        r12export.saveas(doc, out)
    else:
        doc.saveas(out)
    print(f"ok {out}")


if __name__ == "__main__":
    main(sys.argv[1:])
