"""TDMS fixtures for tests/import_tdms.rs, written and read by npTDMS (another TDMS writer than
dlw's reader, installed by scripts/test.sh).

    tdms_fixture.py write SPEC.json OUT.tdms   one TdmsWriter.write_segment call per segment
    tdms_fixture.py read IN.tdms OUT.json      every channel's values as npTDMS reads them
                                               (scaled), and its properties
    tdms_fixture.py bench DAQ.csv OUT.tdms N   a DAQ CSV export (Time,AI0,AI1,AI2) as N
                                               segments: AI0 i16 with a linear scale (a 16-bit
                                               ±10 V input), AI1 f64, AI2 f32, waveform
                                               properties, no time channel

SPEC.json: {"segments": [[{"group": G, "channel": C or null, "dtype": "float64"|"float32"|
"int16"|"int32"|..., "values": [...], "properties": {name: value}}, ...], ...]}; a property
given as {"timestamp": "2026-11-25T18:00:00.250"} is written as a TDMS timestamp.
"""

import json
import sys

import numpy as np
from nptdms import ChannelObject, GroupObject, RootObject, TdmsFile, TdmsWriter


def properties(spec):
    out = {}
    for name, value in (spec or {}).items():
        if isinstance(value, dict) and "timestamp" in value:
            out[name] = np.datetime64(value["timestamp"], "us")
        else:
            out[name] = value
    return out


def write(spec_path, out_path):
    with open(spec_path) as f:
        spec = json.load(f)
    with TdmsWriter(out_path) as writer:
        for segment in spec["segments"]:
            objects = []
            for obj in segment:
                props = properties(obj.get("properties"))
                if obj.get("group") is None:
                    objects.append(RootObject(props))
                elif obj.get("channel") is None:
                    objects.append(GroupObject(obj["group"], props))
                else:
                    data = np.array(obj["values"], dtype=obj["dtype"])
                    objects.append(ChannelObject(obj["group"], obj["channel"], data, properties=props))
            writer.write_segment(objects)


def read(in_path, out_path):
    channels = {}
    for group in TdmsFile.read(in_path).groups():
        for channel in group.channels():
            data = channel[:]
            numeric = getattr(data, "dtype", None) is not None and data.dtype.kind in "fiub"
            channels[f"{group.name}/{channel.name}"] = {
                "values": [float(v) for v in data] if numeric else [str(v) for v in data],
                "properties": {k: str(v) for k, v in channel.properties.items()},
            }
    with open(out_path, "w") as f:
        json.dump(channels, f)


def bench(csv_path, out_path, segments):
    data = np.loadtxt(csv_path, delimiter=",", skiprows=1)
    hz = round(1.0 / np.median(np.diff(data[:, 0])), 6)
    # A ±10 V, 16-bit input: counts times 10/32768 V, less a 2 mV offset.
    slope, intercept = 10.0 / 32768.0, -0.002
    counts = np.round((data[:, 1] - intercept) / slope).astype(np.int16)
    start = np.datetime64("2026-11-25T18:00:00.000000", "us")
    with TdmsWriter(out_path) as writer:
        for k, rows in enumerate(np.array_split(np.arange(len(data)), segments)):
            wf = {"wf_increment": 1.0 / hz, "wf_samples": len(rows)}
            if k == 0:
                wf["wf_start_time"] = start
                wf["wf_start_offset"] = 0.0
            scale = dict(wf)
            if k == 0:
                scale.update({
                    "NI_Number_Of_Scales": 1,
                    "NI_Scale[0]_Scale_Type": "Linear",
                    "NI_Scale[0]_Linear_Slope": slope,
                    "NI_Scale[0]_Linear_Y_Intercept": intercept,
                })
            writer.write_segment([
                RootObject({"name": "bench"}) if k == 0 else RootObject(),
                GroupObject("daq"),
                ChannelObject("daq", "AI0", counts[rows], properties=scale),
                ChannelObject("daq", "AI1", data[rows, 2].astype(np.float64), properties=wf),
                ChannelObject("daq", "AI2", data[rows, 3].astype(np.float32), properties=wf),
            ])


if __name__ == "__main__":
    mode = sys.argv[1]
    if mode == "write":
        write(sys.argv[2], sys.argv[3])
    elif mode == "read":
        read(sys.argv[2], sys.argv[3])
    elif mode == "bench":
        bench(sys.argv[2], sys.argv[3], int(sys.argv[4]))
    else:
        sys.exit(f"unknown mode {mode!r}")
