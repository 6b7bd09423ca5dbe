#!/usr/bin/env python3
"""Writes the MED files of tests/med_layouts.rs: one small MED 2.x mesh (no computation
step, 32-bit integers, as MED 2.3 wrote it) in every HDF5 data-layout message version and
storage class that HDF5 writers have produced:

  v1_contiguous, v1_chunked                 layout version 1 (HDF5 1.4 and earlier)
  v2_contiguous, v2_chunked, v2_compact     layout version 2 (HDF5 1.6.0-1.6.2)
  v3_contiguous, v3_chunked, v3_compact     layout version 3 (libver 'earliest')
  v4_contiguous, v4_chunked, v4_compact     layout version 4 (libver 'latest')

h5py writes versions 3 and 4. No current library writes versions 1 and 2, so this script
writes the version 3 file and then re-encodes each dataset's layout message in place,
following "The Data Layout Message" of the HDF5 file format specification: version, rank
+ 1, class, five reserved bytes, the address (not for compact), rank + 1 four-byte
dimensions ending with the element size, and for compact a four-byte size and the data.
The version 1/2 message is longer than the version 3 one; the extra bytes come from the
NIL (free space) message libhdf5 leaves at the end of the object header. `h5dump` (libhdf5)
reads every file written here: run with --check to verify that.

Usage: python3 make.py [--check]   (needs h5py; writes next to this script)
"""
import os
import struct
import subprocess
import sys

import h5py
import numpy as np
from h5py import h5d, h5o, h5p

HERE = os.path.dirname(os.path.abspath(__file__))

# The mesh: two quadrangles and a triangle, two boundary edges (Seg2), 7 nodes.
#   3 --- 4 --- 5
#   |  q1 |  q2 |  \ t
#   0 --- 1 --- 2 -- 6
COO = [(0, 0), (1, 0), (2, 0), (0, 1), (1, 1), (2, 1), (3, 0.5)]
# Cells in MED's clockwise order, 1-based.
QU4 = [(1, 4, 5, 2), (2, 5, 6, 3)]
TR3 = [(3, 6, 7)]
SE2 = [(1, 2), (2, 3)]
# Families: cells negative, nodes positive, 0 none.
QU4_FAM = [-1, -2]
TR3_FAM = [-2]
SE2_FAM = [-3, -3]
NODE_FAM = [1, 0, 0, 0, 0, 0, 2]
FAMILIES = {
    "ELEME": {"FAM_-1": (-1, ["left", "body"]), "FAM_-2": (-2, ["right", "body"]),
              "FAM_-3": (-3, ["bottom"])},
    "NOEUD": {"FAM_1": (1, ["corner"]), "FAM_2": (2, ["tip"])},
}
MESH = "old"


def no_interlace(rows):
    return np.array([v for k in range(len(rows[0])) for v in (r[k] for r in rows)])


def write_mesh(path, libver, storage):
    """The MED 2.x structure, every dataset with `storage` (contiguous/chunked/compact)."""

    def dataset(group, name, data, count=None):
        kw = {}
        if storage == "chunked":
            kw["chunks"] = (max(1, min(4, len(data))),)  # several chunks per dataset
        elif storage == "compact":
            dcpl = h5p.create(h5p.DATASET_CREATE)
            dcpl.set_layout(h5d.COMPACT)
            kw["dcpl"] = dcpl
        ds = group.create_dataset(name, data=data, **kw)
        if count is not None:
            ds.attrs.create("NBR", count, dtype="<i4")
        return ds

    with h5py.File(path, "w", libver=libver) as f:
        info = f.create_group("INFOS_GENERALES")
        for k, v in (("MAJ", 2), ("MIN", 3), ("REL", 6)):
            info.attrs.create(k, v, dtype="<i4")
        m = f.create_group("ENS_MAA").create_group(MESH)
        for k, v in (("DIM", 2), ("ESP", 2), ("TYP", 0), ("REP", 0)):
            m.attrs.create(k, v, dtype="<i4")
        noe = m.create_group("NOE")
        dataset(noe, "COO", no_interlace(COO).astype("<f8"), len(COO))
        dataset(noe, "FAM", np.array(NODE_FAM, dtype="<i4"), len(COO))
        mai = m.create_group("MAI")
        for name, cells, fams in (("QU4", QU4, QU4_FAM), ("TR3", TR3, TR3_FAM),
                                  ("SE2", SE2, SE2_FAM)):
            g = mai.create_group(name)
            dataset(g, "NOD", no_interlace(cells).astype("<i4"), len(cells))
            dataset(g, "FAM", np.array(fams, dtype="<i4"), len(cells))
        fas = f.create_group("FAS").create_group(MESH)
        for kind, fams in FAMILIES.items():
            k = fas.create_group(kind)
            for fname, (num, groups) in fams.items():
                g = k.create_group(fname)
                g.attrs.create("NUM", num, dtype="<i4")
                names = b"".join(n.encode().ljust(80, b"\0") for n in groups)
                dataset(g.create_group("GRO"), "NOM",
                        np.frombuffer(names, dtype="i1"), len(groups))


def datasets(path):
    """(object header address, dataset shape, element size) of every dataset."""
    out = []
    with h5py.File(path, "r") as f:
        def visit(_, obj):
            if isinstance(obj, h5py.Dataset):
                out.append((h5o.get_info(obj.id).addr, obj.shape, obj.dtype.itemsize))
        f.visititems(visit)
    return out


def old_layout(version, body, shape, elem):
    """A version 3 layout message body re-encoded as version `version` (1 or 2)."""
    assert body[0] == 3, f"expected a version 3 layout message, got {body[0]}"
    cls = body[1]
    dims = list(shape) + [elem]
    head = struct.pack("<BBB5x", version, len(dims), cls)
    if cls == 1:  # contiguous: address, size -> address, dimensions
        addr = body[2:10]
        return head + addr + struct.pack(f"<{len(dims)}I", *dims)
    if cls == 2:  # chunked: ndims, B-tree address, chunk dims (ending with the element size)
        ndims = body[2]
        addr = body[3:11]
        chunk = body[11:11 + 4 * ndims]
        return struct.pack("<BBB5x", version, ndims, cls) + addr + chunk
    if cls == 0:  # compact: u16 size, data -> dimensions, u32 size, data
        assert version == 2, "layout version 1 has no compact storage"
        (n,) = struct.unpack_from("<H", body, 2)
        return head + struct.pack(f"<{len(dims)}I", *dims) + struct.pack("<I", n) + body[4:4 + n]
    raise ValueError(f"layout class {cls}")


def rewrite_layouts(path, version):
    """Re-encodes the layout message of every dataset (version 1 object headers): the
    header's messages are laid out again in the same block, the final NIL message
    (free space) shrinking by what the longer layout message takes."""
    found = datasets(path)
    data = bytearray(open(path, "rb").read())
    for addr, shape, elem in found:
        assert data[addr] == 1, "version 1 object header expected"
        (nmsgs,) = struct.unpack_from("<H", data, addr + 2)
        (hsize,) = struct.unpack_from("<I", data, addr + 8)
        msgs, p = [], addr + 16
        while p < addr + 16 + hsize:
            mtype, msize, flags = struct.unpack_from("<HHB", data, p)
            msgs.append((mtype, flags, bytes(data[p + 8:p + 8 + msize])))
            p += 8 + msize
        assert len(msgs) == nmsgs, "the header is in one block (no continuation)"
        assert msgs[-1][0] == 0, "the header ends with free space (a NIL message)"
        out = []
        for mtype, flags, body in msgs[:-1]:
            if mtype == 8:
                body = old_layout(version, body, shape, elem)
                body = body.ljust((len(body) + 7) // 8 * 8, b"\0")
            out.append(struct.pack("<HHB3x", mtype, len(body), flags) + body)
        used = sum(map(len, out))
        assert used + 8 <= hsize, f"no room for the longer layout message ({used}/{hsize})"
        out.append(struct.pack("<HHB3x", 0, hsize - used - 8, 0) + bytes(hsize - used - 8))
        data[addr + 16:addr + 16 + hsize] = b"".join(out)
    open(path, "wb").write(bytes(data))


def main():
    files = []
    for storage in ("contiguous", "chunked", "compact"):
        for version in (1, 2, 3, 4):
            if version == 1 and storage == "compact":
                continue
            path = os.path.join(HERE, f"v{version}_{storage}.med")
            write_mesh(path, "latest" if version == 4 else "earliest", storage)
            if version < 3:
                rewrite_layouts(path, version)
            files.append(path)
    if "--check" in sys.argv:
        for path in files:
            subprocess.run(["h5dump", "-o", os.devnull, path], check=True,
                           stdout=subprocess.DEVNULL)
            out = subprocess.run(["h5dump", "-p", "-d", f"/ENS_MAA/{MESH}/NOE/COO", path],
                                 check=True, capture_output=True, text=True).stdout
            assert "0, 1, 2, 0, 1, 2, 3" in " ".join(out.split()), out
            print("h5dump reads", os.path.basename(path))
    for path in files:
        print(os.path.basename(path), os.path.getsize(path), "bytes")


if __name__ == "__main__":
    main()
