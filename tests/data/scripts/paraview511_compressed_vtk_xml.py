# Writes the VTK XML fixtures with ParaView 5.11's own VTK (pvpython): 20 particles on a
# 5 x 4 grid, arrays id (Int64), radius (Float32), strain (Float64), written as an
# UnstructuredGrid of vertices with each of VTK's compressors.
from vtkmodules.vtkCommonCore import vtkPoints, vtkFloatArray, vtkDoubleArray, vtkTypeInt64Array
from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid, vtkPolyData, vtkCellArray, VTK_VERTEX
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter, vtkXMLPolyDataWriter
import sys

def grid():
    pts = vtkPoints()
    pts.SetDataTypeToDouble()
    ids = vtkTypeInt64Array(); ids.SetName("id")
    rad = vtkFloatArray(); rad.SetName("radius")
    strain = vtkDoubleArray(); strain.SetName("strain")
    for j in range(4):
        for i in range(5):
            k = j * 5 + i
            pts.InsertNextPoint(0.5 * i, 0.25 * j, 0.125 * k)
            ids.InsertNextValue(1000 + k)
            rad.InsertNextValue(0.1 + 0.01 * k)
            strain.InsertNextValue(k / 19.0)
    return pts, ids, rad, strain

def ug():
    pts, ids, rad, strain = grid()
    g = vtkUnstructuredGrid()
    g.SetPoints(pts)
    for k in range(pts.GetNumberOfPoints()):
        g.InsertNextCell(VTK_VERTEX, 1, [k])
    for a in (ids, rad, strain):
        g.GetPointData().AddArray(a)
    return g

def pd():
    pts, ids, rad, strain = grid()
    p = vtkPolyData()
    p.SetPoints(pts)
    verts = vtkCellArray()
    for k in range(pts.GetNumberOfPoints()):
        verts.InsertNextCell(1)
        verts.InsertCellPoint(k)
    p.SetVerts(verts)
    for a in (ids, rad, strain):
        p.GetPointData().AddArray(a)
    return p

for name, comp, mode, kind in [
        ("paraview511_lz4_appended.vtu", "LZ4", "appended", "ug"),
        ("paraview511_lzma_appended.vtu", "LZMA", "appended", "ug"),
        ("paraview511_lz4_inline_base64.vtp", "LZ4", "binary", "pd"),
        ("paraview511_lzma_inline_base64_uint64.vtp", "LZMA", "binary", "pd")]:
    w = vtkXMLUnstructuredGridWriter() if kind == "ug" else vtkXMLPolyDataWriter()
    w.SetInputData(ug() if kind == "ug" else pd())
    w.SetFileName(name)
    getattr(w, "SetCompressorTypeTo" + comp)()
    if mode == "appended":
        w.SetDataModeToAppended()
        w.EncodeAppendedDataOff()  # raw bytes after '_', as ParaView's default save
    else:
        w.SetDataModeToBinary()
    if "uint64" in name:
        w.SetHeaderTypeToUInt64()
    w.SetBlockSize(64)  # several compressed blocks per array
    assert w.Write() == 1, name
    print("wrote", name)
