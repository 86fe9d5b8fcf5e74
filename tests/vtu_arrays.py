"""The data arrays of a vtu file as estep writes it (binary, zlib-compressed), read with the
standard library alone, for the test scripts."""

import base64
import re
import struct
import zlib


def decoded(encoded):
    """The bytes of one array in VTK's compressed binary form: a base64 header (the number of
    blocks, the block size, the last block's size, the compressed size of each block), then the
    zlib blocks one after the other, in base64."""
    blocks = struct.unpack("<I", base64.b64decode(encoded[:8])[:4])[0]
    header_chars = 4 * ((4 * (3 + blocks) + 2) // 3)
    sizes = struct.unpack("<%dI" % (3 + blocks), base64.b64decode(encoded[:header_chars]))[3:]
    data, raw, at = base64.b64decode(encoded[header_chars:]), b"", 0
    for size in sizes:
        raw += zlib.decompress(data[at:at + size])
        at += size
    return raw


def arrays(path):
    """Every data array of the vtu file at path, by name (the points' coordinates as "points"),
    as a tuple of numbers."""
    found = {}
    for kind, name, encoded in re.findall(
            r'<DataArray type="(\w+)"(?: Name="(\w+)")?[^>]*format="binary">\s*(\S+)\s*</DataArray>',
            open(path).read()):
        raw = decoded(encoded)
        code = {"Float32": "f", "Int32": "i", "UInt8": "B"}[kind]
        found[name or "points"] = struct.unpack("<%d%s" % (len(raw) // struct.calcsize(code), code), raw)
    return found
