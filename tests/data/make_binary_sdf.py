"""Writes the binary SDF (bISO-1.0) test fixtures from the ASCII originals.

Run from this folder with the shared data folder beside the repository:
    python3 make_binary_sdf.py ../../../shared/data/topography/sdf
Independent of the Rust reader: follows the 81-byte little-endian header of ISO 25178-71.
"""
import math
import struct
import sys


def read_ascii(path):
    lines = open(path, encoding="latin-1").read().splitlines()
    header, i = {}, 1
    while lines[i].strip() != "*":
        key, value = lines[i].split("=", 1)
        header[key.strip()] = value.strip()
        i += 1
    values = []
    for line in lines[i + 1:]:
        if line.strip() == "*":
            break
        values += [math.nan if t == "BAD" else float(t) for t in line.split()]
    return header, values


def write_binary(path, header, values, data_type, z_scale, convert):
    fmt = {6: "<i", 7: "<d"}[data_type]
    out = b"bISO-1.0"
    out += header["ManufacID"].encode().ljust(10, b"\0")[:10]
    out += header["CreateDate"].encode().ljust(12, b"\0")[:12]
    out += header["ModDate"].encode().ljust(12, b"\0")[:12]
    out += struct.pack("<HH", int(header["NumPoints"]), int(header["NumProfiles"]))
    out += struct.pack("<dddd", float(header["Xscale"]), float(header["Yscale"]), z_scale,
                       float(header["Zresolution"]))
    out += struct.pack("<BBB", 0, data_type, 0)
    assert len(out) == 81
    out += b"".join(struct.pack(fmt, convert(v)) for v in values)
    open(path, "wb").write(out)


src = sys.argv[1]
h, v = read_ascii(f"{src}/mm11_iso2_ascii_binary64.sdf")
write_binary("mm11_iso2_binary_f64.sdf", h, v, 7, float(h["Zscale"]), lambda x: x)
h, v = read_ascii(f"{src}/sdf-1.sdf")
# sdf-1 has 5 decimals in units of Zscale = 1e-6 m: store them as int32 in units of 1e-11 m.
write_binary("sdf-1_binary_int32.sdf", h, v, 6, 1e-11, lambda x: round(x * 1e5))
