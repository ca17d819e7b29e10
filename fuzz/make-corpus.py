#!/usr/bin/env python3
"""Writes fuzz/corpus (small valid seeds per harness) and fuzz/regressions (one file per crash,
hang or silent acceptance listed in issue 13). Run from anywhere; the output is committed, so
this only needs re-running when a seed or regression is added. scripts/fuzz adds the fixtures
of tests/data to the seeds at run time."""
import gzip, os, struct, zlib

here = os.path.dirname(os.path.abspath(__file__))

def put(kind, harness, name, data):
    folder = os.path.join(here, kind, harness)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())

seed = lambda h, n, d: put("corpus", h, n, d)
regression = lambda h, n, d: put("regressions", h, n, d)

tri = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
faces = [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)]

# --- STL
def binary_stl(count=None, extra=b""):
    body = b"".join(struct.pack("<12fH", 0, 0, 1, *tri[a], *tri[b], *tri[c], 0) for a, b, c in faces)
    return b"bender fuzz seed".ljust(80, b" ") + struct.pack("<I", len(faces) if count is None else count) + body + extra
seed("fuzz_mesh_stl", "tetra-binary.stl", binary_stl())
regression("fuzz_mesh_stl", "longer-than-count.stl", binary_stl(count=1))
regression("fuzz_mesh_stl", "zero-count-padding.stl", b"\0" * 84 + b"\0" * 5000)

# --- OBJ
obj = "".join("v %g %g %g\n" % p for p in tri) + "".join("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in faces)
seed("fuzz_mesh_obj", "tetra.obj", obj)
seed("fuzz_mesh_obj", "normals.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n")

# --- PLY
ply_head = "ply\nformat %s 1.0\ncomment seed\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
ascii_body = "".join("%g %g %g\n" % p for p in tri) + "".join("3 %d %d %d\n" % f for f in faces)
seed("fuzz_mesh_ply", "tetra-ascii.ply", ply_head % "ascii" + ascii_body)
binary_body = b"".join(struct.pack("<3f", *p) for p in tri) + b"".join(struct.pack("<B3i", 3, *f) for f in faces)
seed("fuzz_mesh_ply", "tetra-binary.ply", (ply_head % "binary_little_endian").encode() + binary_body)
seed("fuzz_check_ply_structure", "tetra-ascii.ply", ply_head % "ascii" + ascii_body)
seed("fuzz_check_ply_structure", "tetra-binary.ply", (ply_head % "binary_little_endian").encode() + binary_body)
regression("fuzz_mesh_ply", "record-split-over-lines.ply", ply_head % "ascii" + "0 0\n0\n1 0 0\n0 1 0\n0 0 1\n" + "".join("3 %d %d %d\n" % f for f in faces))
regression("fuzz_mesh_ply", "two-records-one-line.ply", ply_head % "ascii" + "0 0 0 1 0 0\n0 1 0\n0 0 1\n" + "".join("3 %d %d %d\n" % f for f in faces) + "3 0 1 2\n")
regression("fuzz_mesh_ply", "comment-over-4k.ply", (ply_head % "ascii").replace("comment seed", "comment " + "c" * 5000) + ascii_body)
regression("fuzz_mesh_ply", "trailing-spaces-over-4k.ply", ply_head % "ascii" + "0 0 0" + " " * 5000 + "\n" + ascii_body.split("\n", 1)[1])

# --- legacy VTK
pts = " ".join("%g %g %g" % p for p in tri)
legacy3 = "# vtk DataFile Version 3.0\nseed\nASCII\nDATASET POLYDATA\nPOINTS 4 float\n%s\nPOLYGONS 4 16\n%s\nPOINT_DATA 4\nSCALARS s float 1\nLOOKUP_TABLE default\n1 2 3 4\n" % (pts, " ".join("3 %d %d %d" % f for f in faces))
legacy51 = "# vtk DataFile Version 5.1\nseed\nASCII\nDATASET POLYDATA\nPOINTS 4 double\n%s\nPOLYGONS 5 12\nOFFSETS vtktypeint64\n0 3 6 9 12\nCONNECTIVITY vtktypeint64\n%s\nCELL_DATA 4\nFIELD FieldData 1\nRegion 1 4 int\n1 1 2 2\n" % (pts, " ".join("%d %d %d" % f for f in faces))
def be(fmt, *v):
    return struct.pack(">" + fmt, *v)
legacybin = (b"# vtk DataFile Version 5.1\nseed\nBINARY\nDATASET POLYDATA\nPOINTS 4 double\n" + b"".join(be("3d", *p) for p in tri) +
             b"\nPOLYGONS 5 12\nOFFSETS vtktypeint64\n" + be("5q", 0, 3, 6, 9, 12) + b"\nCONNECTIVITY vtktypeint64\n" +
             b"".join(be("3q", *f) for f in faces) + b"\n")
for h in ("fuzz_mesh_vtk", "fuzz_check_legacy_vtk"):
    seed(h, "tetra-3.0.vtk", legacy3)
    seed(h, "tetra-5.1.vtk", legacy51)
    seed(h, "tetra-5.1-binary.vtk", legacybin)
head3 = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n"
head51 = head3.replace("3.0", "5.1")
regression("fuzz_mesh_vtk", "polygons-short.vtk", head3 + "POLYGONS 2 8\n3 0 1 2\n3 0\n")
regression("fuzz_mesh_vtk", "polygons-non-numeric.vtk", head3 + "POLYGONS 1 4\n3 0 x 2\n")
regression("fuzz_mesh_vtk", "offsets-out-of-range.vtk", head51 + "POLYGONS 2 3\nOFFSETS vtktypeint64\n0 30\nCONNECTIVITY vtktypeint64\n0 1 2\n")
regression("fuzz_mesh_vtk", "offsets-decreasing.vtk", head51 + "POLYGONS 3 3\nOFFSETS vtktypeint64\n0 3 1\nCONNECTIVITY vtktypeint64\n0 1 2\n")
regression("fuzz_mesh_vtk", "bad-version-line.vtk", "# vtk DataFile Version x\nt\nBINARY\nDATASET POLYDATA\nPOINTS 3 float\n" + "\0" * 36 + "\n")
# Labelled surfaces as Bender writes them: PatchNames/PatchTypes string arrays in the field
# data, in ASCII one line per value ("%XX" escapes), in binary a length before each value (one
# byte 11xxxxxx for short ones), and CellEntityIds per cell.
names, roles = ["wall", "inlet", "outlet_1"], ["wall", "inlet", "outlet"]
ascii_strings = lambda name, values: "%s 1 %d string\n%s\n" % (name, len(values), "\n".join(values))
binary_strings = lambda name, values: ("%s 1 %d string\n" % (name, len(values))).encode() + b"".join(bytes([0xC0 | len(v)]) + v.encode() for v in values) + b"\n"
legacy_labelled = legacy51.replace("DATASET POLYDATA\n", "DATASET POLYDATA\nFIELD FieldData 2\n" + ascii_strings("PatchNames", ["wall", "inlet", "outlet%5F1"]) + ascii_strings("PatchTypes", roles)).replace("Region 1 4 int\n1 1 2 2", "CellEntityIds 1 4 int\n1 1 2 3")
legacy_labelled_bin = (legacybin.replace(b"DATASET POLYDATA\n", b"DATASET POLYDATA\nFIELD FieldData 2\n" + binary_strings("PatchNames", names) + binary_strings("PatchTypes", roles)) +
                       b"CELL_DATA 4\nFIELD FieldData 1\nCellEntityIds 1 4 int\n" + be("4i", 1, 1, 2, 3) + b"\n")
for h in ("fuzz_mesh_vtk", "fuzz_check_legacy_vtk"):
    seed(h, "labelled-5.1.vtk", legacy_labelled)
    seed(h, "labelled-5.1-binary.vtk", legacy_labelled_bin)
# vtkDataReader decodes "%XX" reading two bytes past a lone '%', and allocates whatever length
# a binary string announces.
regression("fuzz_mesh_vtk", "string-lone-percent.vtk", head51 + "FIELD FieldData 1\n" + ascii_strings("PatchNames", ["%"]))
regression("fuzz_mesh_vtk", "string-length-past-end.vtk", head51.replace("ASCII", "BINARY").replace("POINTS 3 float\n0 0 0 1 0 0 0 1 0\n", "POINTS 0 float\n\n").encode() +
           b"FIELD FieldData 1\nPatchNames 1 1 string\n" + be("Q", 1 << 40) + b"wall\n")

# --- VTK XML PolyData: ASCII, and appended zlib-compressed data with UInt64 headers as the
# project writes it.
def vtp_ascii():
    return ('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">\n'
            '<PolyData>\n<Piece NumberOfPoints="4" NumberOfPolys="4">\n<Points>\n'
            '<DataArray type="Float64" NumberOfComponents="3" format="ascii">%s</DataArray>\n</Points>\n<Polys>\n'
            '<DataArray type="Int64" Name="connectivity" format="ascii">%s</DataArray>\n'
            '<DataArray type="Int64" Name="offsets" format="ascii">3 6 9 12</DataArray>\n</Polys>\n</Piece>\n</PolyData>\n</VTKFile>\n'
            % (pts, " ".join("%d %d %d" % f for f in faces)))
def vtp_appended(header_type="UInt64"):
    arrays = [("Float64", 3, "", struct.pack("<12d", *[c for p in tri for c in p]), "Points"),
              ("Int64", 1, ' Name="connectivity"', struct.pack("<12q", *[i for f in faces for i in f]), "Polys"),
              ("Int64", 1, ' Name="offsets"', struct.pack("<4q", 3, 6, 9, 12), "Polys")]
    blob = b""
    tags = {"Points": "", "Polys": ""}
    for t, n, name, raw, section in arrays:
        comp = zlib.compress(raw)
        tags[section] += '<DataArray type="%s"%s NumberOfComponents="%d" format="appended" offset="%d"/>\n' % (t, name, n, len(blob))
        blob += struct.pack("<4Q", 1, len(raw), len(raw), len(comp)) + comp
    return (('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="%s" compressor="vtkZLibDataCompressor">\n'
             '<PolyData>\n<Piece NumberOfPoints="4" NumberOfPolys="4">\n<Points>\n%s</Points>\n<Polys>\n%s</Polys>\n</Piece>\n</PolyData>\n'
             '<AppendedData encoding="raw">\n_' % (header_type, tags["Points"], tags["Polys"])).encode() + blob + b"\n</AppendedData>\n</VTKFile>\n")
for h in ("fuzz_mesh_vtp", "fuzz_check_vtk_xml"):
    seed(h, "tetra-ascii.vtp", vtp_ascii())
    seed(h, "tetra-appended.vtp", vtp_appended())
regression("fuzz_mesh_vtp", "header-type-damaged.vtp", vtp_appended("UInt6"))
regression("fuzz_mesh_vtp", "components-1e9.vtp", vtp_ascii().replace('NumberOfComponents="3"', 'NumberOfComponents="1000000000"'))
regression("fuzz_mesh_vtp", "truncated.vtp", vtp_appended()[:-60])

# --- OFF
seed("fuzz_mesh_off", "tetra.off", "OFF\n4 4 0\n" + "".join("%g %g %g\n" % p for p in tri) + "".join("3 %d %d %d\n" % f for f in faces))

# --- volumes: 3x2x2 float
vox = struct.pack("<12f", *range(12))
nrrd_head = "NRRD0004\ntype: float\ndimension: 3\nspace: left-posterior-superior\nsizes: 3 2 2\nspace directions: (1,0,0) (0,1,0) (0,0,1)\nendian: little\nencoding: %s\nspace origin: (0,0,0)\n"
seed("fuzz_check_nrrd", "raw.nrrd", (nrrd_head % "raw" + "\n").encode() + vox)
seed("fuzz_check_nrrd", "gzip.nrrd", (nrrd_head % "gzip" + "\n").encode() + gzip.compress(vox))
seed("fuzz_check_nrrd", "ascii.nrrd", nrrd_head % "ascii" + "\n" + " ".join(str(i) for i in range(12)) + "\n")
seed("fuzz_check_nhdr", "detached.nhdr", nrrd_head % "raw" + "data file: detached.raw\n")
regression("fuzz_check_nrrd", "header-line-2000.nrrd", (nrrd_head % "raw" + "content: " + "a" * 2000 + "\n\n").encode() + vox)
regression("fuzz_check_nrrd", "ascii-value-100k.nrrd", nrrd_head % "ascii" + "\n" + "7" * 100000 + "\n")
regression("fuzz_check_nrrd", "truncated-raw.nrrd", (nrrd_head % "raw" + "\n").encode() + vox[:-8])
meta_head = "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\nCompressedData = %s\n%sTransformMatrix = 1 0 0 0 1 0 0 0 1\nOffset = 0 0 0\nElementSpacing = 1 1 1\nDimSize = 3 2 2\nElementType = MET_FLOAT\nElementDataFile = %s\n"
comp = zlib.compress(vox)
seed("fuzz_check_mha", "raw.mha", (meta_head % ("False", "", "LOCAL")).encode() + vox)
seed("fuzz_check_mha", "zlib.mha", (meta_head % ("True", "CompressedDataSize = %d\n" % len(comp), "LOCAL")).encode() + comp)
seed("fuzz_check_mhd", "detached.mhd", meta_head % ("False", "", "detached.raw"))
regression("fuzz_check_mha", "field-name-300.mha", ("ObjectType = Image\n" + "K" * 300 + " = 1\n" + meta_head.split("\n", 1)[1] % ("False", "", "LOCAL")).encode() + vox)
regression("fuzz_check_mha", "ndims-negative.mha", (meta_head % ("False", "", "LOCAL")).replace("NDims = 3", "NDims = -1").encode() + vox)
regression("fuzz_check_mha", "ndims-huge.mha", (meta_head % ("False", "", "LOCAL")).replace("NDims = 3", "NDims = 2000000000").encode() + vox)
regression("fuzz_check_mha", "truncated-zlib.mha", (meta_head % ("True", "", "LOCAL")).encode() + comp[:-6])
regression("fuzz_check_mha", "truncated-raw.mha", (meta_head % ("False", "", "LOCAL")).encode() + vox[:-4])
def nifti(datalen=None):
    h = bytearray(352)
    struct.pack_into("<i", h, 0, 348)
    struct.pack_into("<8h", h, 40, 3, 3, 2, 2, 1, 1, 1, 1)
    struct.pack_into("<hh", h, 70, 16, 32)
    struct.pack_into("<8f", h, 76, 1, 1, 1, 1, 1, 1, 1, 1)
    struct.pack_into("<f", h, 108, 352.0)
    struct.pack_into("<hh", h, 252, 1, 1)
    h[344:348] = b"n+1\0"
    return bytes(h) + (vox if datalen is None else vox[:datalen])
seed("fuzz_check_nii", "float.nii", nifti())
seed("fuzz_check_niigz", "float.nii.gz", gzip.compress(nifti()))
regression("fuzz_check_nii", "truncated.nii", nifti(40))
regression("fuzz_check_niigz", "truncated.nii.gz", gzip.compress(nifti())[:-20])
vti = ('<?xml version="1.0"?>\n<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" header_type="UInt64">\n'
       '<ImageData WholeExtent="0 2 0 1 0 1" Origin="0 0 0" Spacing="1 1 1" Direction="1 0 0 0 1 0 0 0 1">\n<Piece Extent="0 2 0 1 0 1">\n'
       '<PointData Scalars="s">\n<DataArray type="Float32" Name="s" format="ascii">%s</DataArray>\n</PointData>\n<CellData>\n</CellData>\n</Piece>\n</ImageData>\n</VTKFile>\n'
       % " ".join(str(i) for i in range(12)))
seed("fuzz_check_vti", "ascii.vti", vti)
regression("fuzz_check_vti", "truncated.vti", vti[:-40])

# --- replay timestamps for the harness's 256-byte recording; Fastrak; plans; messages
seed("fuzz_replay", "valid.timestamps", "# bender tracking recording v1: offset bytes seconds\n0 64 0.1\n64 64 0.2\n128 128 0.35\n")
regression("fuzz_replay", "size-wraps-64-bits.timestamps", "0 64 0.1\n64 18446744073709551600 0.2\n")
regression("fuzz_replay", "time-1e300.timestamps", "0 128 0.1\n128 128 1e300\n")
regression("fuzz_replay", "escape-sequences.timestamps", "0 64 \x1b[31mred\x1b]0;title\x07\n")
seed("fuzz_message", "vtk.txt", "ERROR: In ./IO/XML/vtkXMLReader.cxx, line 521\nvtkXMLPolyDataReader (0x55d0c3a0): Error parsing XML\n\n")
seed("fuzz_message", "itk.txt", "\x1b[1;31mITK ERROR: MetaImageIO(0x55d0c3a0): File cannot be read\x1b[0m\n[nrrd] nrrdLoad: trouble\n")
seed("fuzz_fastrak", "binary-record", b"\x00" + b"01 " + struct.pack("<7f", 1, 2, 3, 1, 0, 0, 0) + b" 0 ")
seed("fuzz_fastrak", "ascii-record", b"\x01" + b"01   30.01 -150.70   12.00 1.0000 0.0000 0.0000 0.0000 0 ")

# --- Fastrak under arbitrary chunking: first byte = format | units << 1 | (chunk bytes) << 2
fastrak_binary = b"".join(b"0%d " % s + struct.pack("<7f", 10.5 * s, -3, 2, 1, 0, 0, 0) + b" %d " % (s - 1) for s in (1, 2))
fastrak_ascii = b"01   30.01 -150.70   12.00 1.0000 0.0000 0.0000 0.0000 0 \r\n02    1.00    2.00    3.00 0.7071 0.7071 0.0000 0.0000 1 \r\n"
seed("fuzz_fastrak_chunks", "binary-split-1-7-33", bytes([0 | 3 << 2, 0, 6, 32]) + fastrak_binary * 3)
seed("fuzz_fastrak_chunks", "ascii-split-5-54", bytes([1 | 2 << 2, 4, 53]) + fastrak_ascii * 2)
seed("fuzz_fastrak_chunks", "binary-garbage-between", bytes([0 | 1 << 2, 16]) + b"\xff0\x001" + fastrak_binary + b"02x" + fastrak_binary)

# --- OpenIGTLink: first byte = (chunk bytes) | (body limit: 0 64 MiB, 1 1024, 2 48, 3 0) << 4,
# then the chunk sizes minus one, then the stream. The CRC is the protocol's CRC-64 (ECMA-182
# polynomial, no reflection, initial value 0), as igtl_util's crc64.
def crc64(data):
    crc = 0
    for byte in data:
        crc ^= byte << 56
        for _ in range(8):
            crc = ((crc << 1) ^ 0x42F0E1EBA9EA3693) if crc & (1 << 63) else crc << 1
            crc &= (1 << 64) - 1
    return crc

def igtl(kind, name, content, version=1, metadata=(), timestamp=0, message_id=0, announce=None):
    body = content
    if version == 2:
        values = b"".join(k + v for k, v in metadata)
        index = (struct.pack(">H", len(metadata)) + b"".join(struct.pack(">HHI", len(k), 3, len(v)) for k, v in metadata)) if metadata else b""
        body = struct.pack(">HHII", 12, len(index), len(values), message_id) + content + index + values
    size = len(body) if announce is None else announce
    return struct.pack(">H12s20sQQQ", version, kind, name, timestamp, size, crc64(body)) + body

def floats(*v):
    return struct.pack(">%df" % len(v), *v)

transform = floats(0, 1, 0, -1, 0, 0, 0, 0, 1, 10, 20, 30)  # rotation columns, then translation
qtdata = b"".join(struct.pack(">20sBB", n, 5, 0) + floats(1, 2, 3, 0, 0, 0.6, 0.8) for n in (b"StylusToTracker", b"Stylus2ToTracker"))
tdata = struct.pack(">20sBB", b"Stylus2ToTracker", 5, 0) + transform
string = struct.pack(">HH", 3, 4) + b"down"
status = struct.pack(">HQ20s", 4, 0, b"NotReady") + b"tool out of view\0"
messages = {
    "transform": igtl(b"TRANSFORM", b"StylusToTracker", transform, timestamp=(12 << 32) | 5),
    "position-28": igtl(b"POSITION", b"Stylus2ToTracker", floats(1, 2, 3, 0, 0, 0, 1)),
    "position-12": igtl(b"POSITION", b"StylusToTracker", floats(4, 5, 6)),
    "qtdata": igtl(b"QTDATA", b"Tracker", qtdata),
    "tdata": igtl(b"TDATA", b"Tracker", tdata),
    "string-button": igtl(b"STRING", b"StylusToTracker", string),
    "status": igtl(b"STATUS", b"Tracker", status),
    "v2-transform-metadata": igtl(b"TRANSFORM", b"StylusToTracker", transform, 2, [(b"TransformStatus", b"OK"), (b"Source", b"PLUS")], message_id=7),
    "v2-image-skipped": igtl(b"IMAGE", b"Image", bytes(200), 2, [(b"a", b"b")]),
}
for name, stream in messages.items():
    seed("fuzz_igtl", name, bytes([0]) + stream)
seed("fuzz_igtl", "all-split-1-13-58", bytes([3, 0, 12, 57]) + b"".join(messages.values()))
damaged = bytearray(messages["transform"])
damaged[70] ^= 0x40
seed("fuzz_igtl", "garbage-crc-error-then-message", bytes([2, 4, 100]) + b"\xde\xad\x00\x01x" + bytes(damaged) + messages["position-28"] + b"\xff" * 60 + messages["qtdata"])
seed("fuzz_igtl", "announces-2-to-60", bytes([1, 57]) + igtl(b"IMAGE", b"Image", b"", announce=1 << 60) + messages["transform"])
seed("fuzz_igtl", "limit-48-image-refused", bytes([2 << 4]) + messages["transform"] + messages["v2-image-skipped"])
# Described messages (first byte bit 6): kind (type index | version 2 << 3), name, content.
def described(kind, name, content, metadata=()):
    out = bytes([kind, len(name)]) + name + struct.pack(">H", len(content)) + content
    if kind & 8:
        out += bytes([len(metadata)]) + b"".join(bytes([len(k)]) + k + bytes([len(v)]) + v for k, v in metadata)
    return out
seed("fuzz_igtl", "described-all-types", bytes([0x40 | 2, 9, 30]) + described(0, b"StylusToTracker", transform) +
     described(1, b"Stylus2ToTracker", floats(1, 2, 3, 0, 0, 0, 1)) + described(2, b"Tracker", qtdata) +
     described(3, b"Tracker", tdata) + described(4, b"StylusToTracker", string) + described(5, b"Tracker", status) +
     described(8 | 6, b"Image", bytes(30), [(b"k", b"v")]))
# The captured bytes of Bender's own IgtlSender (fuzz/corpus/fuzz_igtl/igtl-send-*) are not
# written here: `bender-cli igtl-send tests/data/io/tetra_ascii.stl --to HOST:PORT` (and with
# `--plan tests/data/io/example.bender.json`) received by a plain TCP server, a control byte
# in front (0, and 2 with chunk sizes 64 and 9).
# Found by fuzz_igtl (issue 25): a STATUS text with bytes outside printable ASCII reached the
# status line as they were; a QTDATA element name with control bytes reached the names shown.
regression("fuzz_igtl", "qtdata-element-name-not-printable", bytes([0x40]) + described(2, b"Tracker", struct.pack(">20sBB", b"Stylus\x1b[31m", 5, 0) + floats(1, 2, 3, 0, 0, 0, 1)))

# --- session (autosave) files: version 1 (source, name, frame, plan) and version 2 with every
# optional part, the plan being the IO tests' example.
import json
plan = json.load(open(os.path.join(here, "..", "tests", "data", "io", "example.bender.json")))
session1 = {"format": "bender-session", "version": 1, "source": "/data/aneurysm.stl", "frame": "LPS", "plan": plan}
end = lambda x: {"position": [x, 0, 0], "tangent": [1, 0, 0], "normal": [0, 0, 1]}
session2 = dict(session1, version=2, name="aneurysm.stl (segmented)",
    volume={"path": "/data/mra.nrrd", "name": "mra", "series": "1.2.3", "size": [64, 64, 32], "spacing": [0.5, 0.5, 1.0],
            "origin": [-10.0, 5.5, 0.0], "direction": [1, 0, 0, 0, 1, 0, 0, 0, 1], "mask": "/tmp/autosave.mask.nrrd"},
    segmentation={"method": "vesselness", "lower": 100.0, "upper": 900.5, "seeds": [[1, 2, 3]], "fillHoles": True,
                  "closingRadius": 1.0, "minRadius": 0.5, "maxRadius": 4.0, "scales": 4, "alpha": 0.5, "beta": 0.5,
                  "gamma": 5.0, "vesselnessThreshold": 0.05, "brightVessels": True, "levelSetIterations": 10,
                  "levelSetSigma": 1.0, "levelSetPropagation": 0.0, "levelSetCurvature": 1.0, "extractor": "vtk",
                  "smoothing": 0.5, "targetTriangles": 20000, "surfaceSeeds": [[0, 0, 0]]},
    ribbon={"start": end(0), "end": end(40), "extraTurns": 0, "radius": 12.5, "decay": "plateau", "plateau": 0.5,
            "vesselRadius": 2.5})
seed("fuzz_session", "version-1.bender-session.json", json.dumps(session1, indent=2))
seed("fuzz_session", "version-2-full.bender-session.json", json.dumps(session2, indent=2))
