"""Writes tiny_int32_masked.x3p, a hand-made X3P exercising the tolerated deviations.

3 x 2 points, int32 heights z = raw * 1e-9 m + 1e-6 m, point (ix=1, iy=0) marked invalid in
bindata/valid.bin, main.xml in a sub-folder with a namespace-free root, an empty <Offset/>
for CX, an en-dash Revision, and the MD5 sums of main.xml (md5checksum.hex) and of the data
members (MD5ChecksumPointData, MD5ChecksumValidPoints). Run: python3 make_x3p_fixture.py
"""
import hashlib
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
<MD5ChecksumPointData>{data_md5}</MD5ChecksumPointData>
<ValidPointsLink>bindata/valid.bin</ValidPointsLink>
<MD5ChecksumValidPoints>{valid_md5}</MD5ChecksumValidPoints></DataLink></Record3>
<Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4></ISO5436>
"""

raw = [10, -20, 30, 40, 50, -60]
data = b"".join(struct.pack("<i", v) for v in raw)
valid = bytes([0b111101])
main_xml = MAIN_XML.format(
    data_md5=hashlib.md5(data).hexdigest().upper(), valid_md5=hashlib.md5(valid).hexdigest()
).encode()
with zipfile.ZipFile("tiny_int32_masked.x3p", "w", zipfile.ZIP_DEFLATED) as z:
    z.writestr("__MACOSX/._scan", b"\0" * 16)
    z.writestr("scan/main.xml", main_xml)
    z.writestr("scan/bindata/data.bin", data)
    z.writestr("scan/bindata/valid.bin", valid)
    z.writestr("scan/md5checksum.hex", hashlib.md5(main_xml).hexdigest().encode() + b" *main.xml\n")
