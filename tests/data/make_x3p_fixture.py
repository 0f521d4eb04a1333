"""Writes tiny_int32_masked.x3p, a hand-made X3P exercising the tolerated deviations.

3 x 2 points, int32 heights z = raw * 1e-9 m + 1e-6 m, point (ix=1, iy=0) marked invalid in
bindata/valid.bin, main.xml in a sub-folder with a namespace-free root, an empty <Offset/>
for CX, and an en-dash Revision. Run: python3 make_x3p_fixture.py
"""
import struct
import zipfile

MAIN_XML = """<?xml version="1.0" encoding="UTF-8"?><ISO5436>
<Record1><Revision>ISO5436 \u2013 2000</Revision><FeatureType>SUR</FeatureType><Axes>
<CX><AxisType>I</AxisType><DataType>D</DataType><Increment>2e-6</Increment><Offset/></CX>
<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>5e-6</Increment><Offset>1e-3</Offset></CY>
<CZ><AxisType>A</AxisType><DataType>L</DataType><Increment>1e-9</Increment><Offset>1e-6</Offset></CZ>
</Axes></Record1>
<Record2><Instrument><Manufacturer>asperity test</Manufacturer></Instrument></Record2>
<Record3><MatrixDimension><SizeX>3</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ></MatrixDimension>
<DataLink><PointDataLink>bindata/data.bin</PointDataLink>
<ValidPointsLink>bindata/valid.bin</ValidPointsLink></DataLink></Record3>
<Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4></ISO5436>
"""

raw = [10, -20, 30, 40, 50, -60]
with zipfile.ZipFile("tiny_int32_masked.x3p", "w", zipfile.ZIP_DEFLATED) as z:
    z.writestr("__MACOSX/._scan", b"\0" * 16)
    z.writestr("scan/main.xml", MAIN_XML.encode())
    z.writestr("scan/bindata/data.bin", b"".join(struct.pack("<i", v) for v in raw))
    z.writestr("scan/bindata/valid.bin", bytes([0b111101]))
    z.writestr("scan/md5checksum.hex", b"0" * 32)
