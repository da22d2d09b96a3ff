"""STEP files for the tests, made with OpenCASCADE itself (OCP, the ``plumbob[cad]`` extra):
closed-form solids in millimetres, a named two-part assembly, and broken shapes."""

from __future__ import annotations


def _writer(unit: str = "MM"):
    from OCP.Interface import Interface_Static

    Interface_Static.SetCVal_s("write.step.unit", unit)


def write_shape(shape, path: str, unit: str = "MM") -> str:
    """``shape`` as a STEP file (AP214) in ``unit``."""
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer

    _writer(unit)
    writer = STEPControl_Writer()
    writer.Transfer(shape, STEPControl_AsIs)
    assert writer.Write(str(path)) == IFSelect_RetDone
    return str(path)


def cylinder(r: float, h: float):
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder

    return BRepPrimAPI_MakeCylinder(r, h).Shape()


def sphere(r: float):
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeSphere

    return BRepPrimAPI_MakeSphere(r).Shape()


def cone(r: float, h: float):
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCone

    return BRepPrimAPI_MakeCone(r, 0.0, h).Shape()


def torus(big: float, small: float):
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeTorus

    return BRepPrimAPI_MakeTorus(big, small).Shape()


def box_with_holes(a: float, b: float, c: float, r: float, centres):
    """An a × b × c box with vertical round holes of radius ``r`` through it at ``centres``."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt

    shape = BRepPrimAPI_MakeBox(a, b, c).Shape()
    for x, y in centres:
        hole = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, y, -1.0), gp_Dir(0, 0, 1)), r, c + 2).Shape()
        shape = BRepAlgoAPI_Cut(shape, hole).Shape()
    return shape


def moved(shape, x: float, y: float, z: float):
    from OCP.gp import gp_Trsf, gp_Vec
    from OCP.TopLoc import TopLoc_Location

    t = gp_Trsf()
    t.SetTranslation(gp_Vec(x, y, z))
    return shape.Moved(TopLoc_Location(t))


def write_assembly(path: str, parts, name: str = "stand") -> str:
    """An XCAF assembly ``name`` of ``parts``: (part name, shape, (x, y, z) placement in mm)."""
    from OCP.gp import gp_Trsf, gp_Vec
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPCAFControl import STEPCAFControl_Writer
    from OCP.STEPControl import STEPControl_AsIs
    from OCP.TCollection import TCollection_ExtendedString
    from OCP.TDataStd import TDataStd_Name
    from OCP.TDocStd import TDocStd_Document
    from OCP.TopLoc import TopLoc_Location
    from OCP.XCAFDoc import XCAFDoc_DocumentTool

    doc = TDocStd_Document(TCollection_ExtendedString("XmlOcaf"))
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    top = tool.NewShape()
    TDataStd_Name.Set_s(top, TCollection_ExtendedString(name))
    labels = {}
    for part, shape, (x, y, z) in parts:
        if part not in labels:
            labels[part] = tool.AddShape(shape, False)
            TDataStd_Name.Set_s(labels[part], TCollection_ExtendedString(part))
        t = gp_Trsf()
        t.SetTranslation(gp_Vec(x, y, z))
        tool.AddComponent(top, labels[part], TopLoc_Location(t))
    tool.UpdateAssemblies()
    _writer("MM")
    writer = STEPCAFControl_Writer()
    writer.Transfer(doc, STEPControl_AsIs)
    assert writer.Write(str(path)) == IFSelect_RetDone
    return str(path)


def face_only():
    """One square face: not a solid."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.gp import gp_Pln

    return BRepBuilderAPI_MakeFace(gp_Pln(), 0.0, 10.0, 0.0, 10.0).Face()


def open_box():
    """A box's shell less its top face: open."""
    from OCP.BRep import BRep_Builder
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS, TopoDS_Shell

    box = BRepPrimAPI_MakeBox(10.0, 10.0, 10.0).Shape()
    shell = TopoDS_Shell()
    builder = BRep_Builder()
    builder.MakeShell(shell)
    explorer, n = TopExp_Explorer(box, TopAbs_FACE), 0
    while explorer.More():
        if n < 5:
            builder.Add(shell, TopoDS.Face(explorer.Current()))
        n += 1
        explorer.Next()
    return shell


def bow_tie_prism():
    """A prism of a self-intersecting (bow-tie) polygon: a solid that crosses itself."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon
    from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
    from OCP.gp import gp_Pnt, gp_Vec

    polygon = BRepBuilderAPI_MakePolygon()
    for x, y in [(0, 0), (10, 10), (10, 0), (0, 10)]:
        polygon.Add(gp_Pnt(x, y, 0))
    polygon.Close()
    face = BRepBuilderAPI_MakeFace(polygon.Wire(), True).Face()
    return BRepPrimAPI_MakePrism(face, gp_Vec(0, 0, 5)).Shape()


def pierced_cube():
    """A 10 mm cube whose corner (10, 10, 10) is pushed down to (10, 10, -2), its faces
    split into planar triangles: the top faces pass through the bottom face. Every face
    is valid and the shell is closed (OpenCASCADE's BRepCheck passes it) and its volume
    is positive (600 mm³): only the faces crossing one another make it not a solid."""
    from OCP.BRepBuilderAPI import (
        BRepBuilderAPI_MakeFace,
        BRepBuilderAPI_MakePolygon,
        BRepBuilderAPI_MakeSolid,
        BRepBuilderAPI_Sewing,
    )
    from OCP.gp import gp_Pnt
    from OCP.TopoDS import TopoDS

    def at(corner):
        return (10, 10, -2) if corner == (10, 10, 10) else corner

    quads = [((0, 0, 0), (0, 10, 0), (10, 10, 0), (10, 0, 0)),
             ((0, 0, 10), (10, 0, 10), (10, 10, 10), (0, 10, 10)),
             ((0, 0, 0), (10, 0, 0), (10, 0, 10), (0, 0, 10)),
             ((0, 10, 0), (0, 10, 10), (10, 10, 10), (10, 10, 0)),
             ((0, 0, 0), (0, 0, 10), (0, 10, 10), (0, 10, 0)),
             ((10, 0, 0), (10, 10, 0), (10, 10, 10), (10, 0, 10))]
    sewing = BRepBuilderAPI_Sewing(1e-6)
    for q in quads:  # outward, each quad as two triangles
        for tri in ((q[0], q[1], q[2]), (q[0], q[2], q[3])):
            polygon = BRepBuilderAPI_MakePolygon()
            for corner in tri:
                polygon.Add(gp_Pnt(*map(float, at(corner))))
            polygon.Close()
            sewing.Add(BRepBuilderAPI_MakeFace(polygon.Wire(), True).Face())
    sewing.Perform()
    return BRepBuilderAPI_MakeSolid(TopoDS.Shell(sewing.SewedShape())).Solid()
