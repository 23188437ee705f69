"""`impactfe export`: the compressed binary VTU + PVD files (default) and the VTKHDF file read back
with xml/zlib and h5py, and the default export with Debian's VTK 9.1 (python3-vtk9): every time
step, every array, compressed; points, cells and cell types, every array the right length, times
increasing from 0, stresses equal to `impactfe post --esol`; superelements as poly-vertex cells;
a reduced run and its expansion as one mesh."""
import os
import struct
import xml.etree.ElementTree as ET
import zlib

import h5py
import numpy as np
import pytest

import impactfe
from conftest import EXAMPLES, post, run

VTK_VERTEX, VTK_POLY_VERTEX, VTK_LINE, VTK_TRIANGLE, VTK_QUAD, VTK_HEXAHEDRON = 1, 2, 3, 5, 9, 12
CELL_OF_TYPE = {"SHELL63": {VTK_TRIANGLE, VTK_QUAD}, "SOLID45": {VTK_HEXAHEDRON},
                "COMBIN40": {VTK_LINE}, "LINK8": {VTK_LINE}, "LINK1": {VTK_LINE},
                "MASS21": {VTK_VERTEX}, "COMBIN14": {VTK_LINE}, "MATRIX50": {VTK_POLY_VERTEX}}
POINT_ARRAYS = ["U", "ROT", "V", "A", "RF", "RM"]


def at_times(column, times):
    """A CSV column (times printed with %.10e) at the exported times."""
    return column.reindex(times, method="nearest", tolerance=1e-9 * max(1.0, times.max())).values


def export(binary, results, out, *extra):
    p = run([binary, "export", results, "-o", str(out), *extra])
    assert p.stdout.startswith("export: wrote "), p.stdout
    return p.stdout


def check_vtkhdf(path, results):
    """Structure of a VTKHDF 2.0 transient UnstructuredGrid; returns (file, steps, n_p, n_c)."""
    r = impactfe.open(results)
    f = h5py.File(path, "r")
    root = f["VTKHDF"]
    assert list(root.attrs["Version"]) == [2, 0]
    assert root.attrs["Type"] == b"UnstructuredGrid"
    n_p = int(root["NumberOfPoints"][0])
    n_c = int(root["NumberOfCells"][0])
    assert n_p == len(r.node_ids)
    assert root["Points"].shape == (n_p, 3)
    np.testing.assert_array_equal(root["Points"][:], r.node_coordinates)
    assert root["Types"].shape == (n_c,) and root["Offsets"].shape == (n_c + 1,)
    assert root["Connectivity"].shape == (int(root["NumberOfConnectivityIds"][0]),)
    assert root["Offsets"][-1] == root["Connectivity"].shape[0]
    assert root["Connectivity"][:].max() < n_p
    # Cell types from the element types (element registry).
    elements = r.elements()
    ids = root["CellData/element_id"][:]
    types = root["Types"][:]
    for eid, t in zip(ids, types):
        assert t in CELL_OF_TYPE[elements.loc[eid, "type_name"]], (eid, t)
    steps = root["Steps"]
    n_s = int(steps.attrs["NSteps"][0])
    times = steps["Values"][:]
    assert len(times) == n_s and times[0] == 0.0 and np.all(np.diff(times) > 0)
    for name in ["PartOffsets", "NumberOfParts", "PointOffsets"]:
        assert steps[name].shape == (n_s,)
    assert steps["CellOffsets"].shape == (n_s, 1)
    assert steps["ConnectivityIdOffsets"].shape == (n_s, 1)
    for name in POINT_ARRAYS:
        assert root["PointData"][name].shape == (n_s * n_p, 3), name
        np.testing.assert_array_equal(steps["PointDataOffsets"][name][:], np.arange(n_s) * n_p)
    for name, ds in root["CellData"].items():
        if name in ("element_id", "type_id", "mat_id"):
            assert ds.shape == (n_c,)
            np.testing.assert_array_equal(steps["CellDataOffsets"][name][:], 0)
        else:
            assert ds.shape == (n_s * n_c,), name
            np.testing.assert_array_equal(steps["CellDataOffsets"][name][:], np.arange(n_s) * n_c)
    return f, times, n_p, n_c


def cell_history(f, times, n_c, item, element):
    cell = list(f["VTKHDF/CellData/element_id"][:]).index(element)
    values = f["VTKHDF/CellData"][item][:].reshape(len(times), n_c)[:, cell]
    return values


def test_helmet_vtkhdf(binary, helmet, tmp_path):
    message = export(binary, helmet, tmp_path, "--format", "vtkhdf")
    assert "ParaView 5.12 or later" in message
    path = tmp_path / "helmet_full.vtkhdf"
    assert str(path) in message
    f, times, n_p, n_c = check_vtkhdf(path, helmet)
    assert n_c == 86  # 72 shells, 4 bricks, 10 gaps: every element drawn
    names = set(f["VTKHDF/CellData"])
    assert {"SEQV_TOP", "SEQV_BOT", "SEQV", "SX", "FORC", "STAT", "DELTA"} <= names
    csv = post(binary, helmet, "--esol", "1,SEQV_TOP", "--esol", "73,SEQV", "--esol",
               "77,FORC", "--esol", "77,STAT", "--nsol", "43,UZ")
    for item, element in [("SEQV_TOP", 1), ("SEQV", 73), ("FORC", 77), ("STAT", 77)]:
        values = cell_history(f, times, n_c, item, element)
        np.testing.assert_allclose(values, at_times(csv[f"E{element}_{item}"], times), rtol=1e-9,
                                   atol=1e-9)
    node = list(impactfe.open(helmet).node_ids).index(43)
    uz = f["VTKHDF/PointData/U"][:].reshape(len(times), n_p, 3)[:, node, 2]
    np.testing.assert_allclose(uz, at_times(csv["N43_UZ"], times), rtol=1e-9, atol=1e-12)
    # A shell has no SAXL/FORC: NaN there, never 0.
    shell = list(f["VTKHDF/CellData/element_id"][:]).index(1)
    assert np.isnan(cell_history(f, times, n_c, "FORC", 1)).all()
    assert shell >= 0
    try:
        import vtk  # Debian python3-vtk9 (VTK 9.1 reads the geometry of a VTKHDF 2.0 file)
    except ImportError:
        return
    reader = vtk.vtkHDFReader()
    reader.SetFileName(str(path))
    reader.Update()
    out = reader.GetOutput()
    assert out.GetNumberOfPoints() == n_p and out.GetNumberOfCells() == n_c
    # Compressed: the per-step arrays are stored with deflate, in chunks of several steps.
    assert f["VTKHDF/PointData/U"].compression == "gzip"
    assert f["VTKHDF/CellData/SEQV_TOP"].compression == "gzip"


def read_vtu(path):
    """Arrays of a binary appended, zlib-compressed VTU (header_type UInt64)."""
    raw = open(path, "rb").read()
    head, data = raw.split(b"<AppendedData encoding=\"raw\">", 1)
    data = data[data.index(b"_") + 1:]
    tree = ET.fromstring(head.decode() + "</VTKFile>")
    assert tree.get("compressor") == "vtkZLibDataCompressor"
    assert tree.get("header_type") == "UInt64"
    piece = tree.find("UnstructuredGrid/Piece")
    dtypes = {"Float64": "<f8", "Int64": "<i8", "Int32": "<i4", "UInt8": "u1"}
    arrays = {}
    for da in piece.iter("DataArray"):
        assert da.get("format") == "appended"
        at = int(da.get("offset"))
        n_blocks, block, last = struct.unpack_from("<QQQ", data, at)
        sizes = struct.unpack_from(f"<{n_blocks}Q", data, at + 24)
        pos = at + 24 + 8 * n_blocks
        out = b""
        for s in sizes:
            out += zlib.decompress(data[pos:pos + s])
            pos += s
        values = np.frombuffer(out, dtype=dtypes[da.get("type")])
        comps = int(da.get("NumberOfComponents", "1"))
        arrays[da.get("Name")] = values.reshape(-1, comps) if comps > 1 else values
    return piece, arrays


def test_helmet_vtu_pvd(binary, helmet, tmp_path):
    message = export(binary, helmet, tmp_path, "--format", "vtu")
    assert "helmet_full.pvd" in message
    pvd = ET.parse(tmp_path / "helmet_full.pvd").getroot()
    datasets = pvd.findall("Collection/DataSet")
    times = np.array([float(d.get("timestep")) for d in datasets])
    assert times[0] == 0.0 and np.all(np.diff(times) > 0)
    r = impactfe.open(helmet)
    seqv = r.history(element=1, item="SEQV_TOP")
    for k in (0, len(datasets) // 2, len(datasets) - 1):
        piece, arrays = read_vtu(tmp_path / datasets[k].get("file"))
        n_p, n_c = int(piece.get("NumberOfPoints")), int(piece.get("NumberOfCells"))
        assert n_p == len(r.node_ids) and n_c == 86
        assert arrays["Points"].shape == (n_p, 3)
        assert arrays["offsets"].shape == (n_c,) and arrays["types"].shape == (n_c,)
        assert arrays["connectivity"].shape == (arrays["offsets"][-1],)
        for name in POINT_ARRAYS:
            assert arrays[name].shape == (n_p, 3)
        for name in ("SEQV_TOP", "FORC", "STAT"):
            assert arrays[name].shape == (n_c,)
        cell = list(arrays["element_id"]).index(1)
        t = times[k]
        assert arrays["SEQV_TOP"][cell] == pytest.approx(seqv.loc[t].iloc[0], rel=1e-12)
    try:
        import vtk
    except ImportError:
        return
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(tmp_path / datasets[-1].get("file")))
    reader.Update()
    out = reader.GetOutput()
    assert out.GetNumberOfPoints() == len(r.node_ids) and out.GetNumberOfCells() == 86
    assert out.GetCellData().GetArray("SEQV_TOP").GetNumberOfTuples() == 86
    assert out.GetPointData().GetArray("U").GetNumberOfComponents() == 3


def test_superelement_use_pass_exports_the_superelement(binary, run_deck, tmp_path_factory):
    out = str(tmp_path_factory.mktemp("se"))
    run_deck(os.path.join(EXAMPLES, "helmet_segen.inp"), directory=out)
    use = run_deck(os.path.join(EXAMPLES, "helmet_use.inp"), directory=out)
    export(binary, use, out, "--format", "vtkhdf")
    f, times, n_p, n_c = check_vtkhdf(os.path.join(out, "helmet_use.vtkhdf"), use)
    types = f["VTKHDF/Types"][:]
    assert (types == VTK_POLY_VERTEX).sum() == 1  # the superelement: its master nodes
    r = impactfe.open(use)
    matrix50 = [e for e, t in r.elements()["type_name"].items() if t == "MATRIX50"]
    assert len(matrix50) == 1
    cell = list(f["VTKHDF/CellData/element_id"][:]).index(matrix50[0])
    offsets = f["VTKHDF/Offsets"][:]
    assert offsets[cell + 1] - offsets[cell] >= 2


def test_reduced_run_and_expansion_are_one_mesh(binary, crash1, tmp_path):
    export(binary, crash1, tmp_path, "--format", "vtkhdf")
    f, times, n_p, n_c = check_vtkhdf(tmp_path / "crash1.vtkhdf", crash1)
    r = impactfe.open(crash1)
    # 61 distinct times although the reduced run (61) and the expansion (60) overlap.
    assert len(times) == 61 and n_c == len(r.elements())
    csv = post(binary, crash1, "--esol", "6,SAXL", "--nsol", "7,UX")
    np.testing.assert_allclose(cell_history(f, times, n_c, "SAXL", 6),
                               at_times(csv["E6_SAXL"], times), rtol=1e-9, atol=1e-9)
    # t = 0 exists only in the reduced run, which has no element results: NaN, not 0.
    assert np.isnan(cell_history(f, times, n_c, "SAXL", 6)[0])


def stored_times(results):
    """The distinct stored times of a results file (every analysis)."""
    with h5py.File(results, "r") as f:
        times = [f[name]["time"][:] for name in f if name.startswith("analysis_")]
    return np.unique(np.concatenate(times))


def test_default_export_opens_every_step_in_debian_vtk(binary, helmet, tmp_path):
    """The default export is the PVD + VTU series, which VTK 9.1 (Debian's python3-vtk9; no
    VTKHDF 2.0 there) reads step by step: every stored time, every array, compressed."""
    message = export(binary, helmet, tmp_path)
    pvd_path = tmp_path / "helmet_full.pvd"
    assert str(pvd_path) in message and "every time step" in message
    vtk = pytest.importorskip("vtk")
    datasets = ET.parse(pvd_path).getroot().findall("Collection/DataSet")
    times = np.array([float(d.get("timestep")) for d in datasets])
    np.testing.assert_allclose(times, stored_times(helmet), rtol=0, atol=0)
    assert len(times) > 10
    r = impactfe.open(helmet)
    n_p = len(r.node_ids)
    uz = r.history(node=43, item="UZ")
    node = list(r.node_ids).index(43)
    raw = 0
    cell_names = None
    for d, t in zip(datasets, times):
        reader = vtk.vtkXMLUnstructuredGridReader()
        reader.SetFileName(str(tmp_path / d.get("file")))
        reader.Update()
        assert reader.GetErrorCode() == 0
        out = reader.GetOutput()
        assert out.GetNumberOfPoints() == n_p and out.GetNumberOfCells() == 86
        pd_, cd = out.GetPointData(), out.GetCellData()
        assert sorted(pd_.GetArrayName(i) for i in range(pd_.GetNumberOfArrays())) == sorted(
            POINT_ARRAYS)
        names = [cd.GetArrayName(i) for i in range(cd.GetNumberOfArrays())]
        assert {"element_id", "SEQV_TOP", "SEQV", "FORC", "STAT"} <= set(names)
        assert cell_names in (None, names)
        cell_names = names
        if t in uz.index:
            assert pd_.GetArray("U").GetTuple3(node)[2] == pytest.approx(uz.loc[t].iloc[0],
                                                                         rel=1e-12, abs=1e-15)
        arrays = [pd_.GetArray(i) for i in range(pd_.GetNumberOfArrays())]
        arrays += [cd.GetArray(i) for i in range(cd.GetNumberOfArrays())]
        arrays += [out.GetPoints().GetData(), out.GetCells().GetConnectivityArray(),
                   out.GetCells().GetOffsetsArray(), out.GetCellTypesArray()]
        raw += sum(a.GetNumberOfValues() * a.GetDataTypeSize() for a in arrays)
    on_disk = sum(os.path.getsize(tmp_path / d.get("file")) for d in datasets)
    print(f"\nhelmet export: {len(times)} time steps, {len(cell_names)} cell + "
          f"{len(POINT_ARRAYS)} point arrays, {on_disk} bytes on disk, {raw} bytes of arrays")
    assert on_disk < 0.7 * raw  # compressed (zlib blocks), not raw
