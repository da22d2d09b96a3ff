"""The OpenCASCADE side of reading a STEP file, run in a child process.

``python -m plumbob.formats.step_worker FILE OUT DEVIATION`` reads ``FILE``
(``--serve``: one such read per line of its standard input, see
:mod:`plumbob.formats.cad_child`) with
OpenCASCADE's XCAF reader (``STEPCAFControl_Reader``: the product structure, names
and placements), and writes to ``OUT`` a pickle of a dict: ``parts``, one entry per
instance of a part (``name``, ``volume`` mm³, ``centre`` (3,) mm, ``inertia`` (3, 3)
mm⁵ — the inertia tensor of unit density about the centre —, ``error`` the integration's
relative error estimate, ``planar`` whether every face is a plane, ``stl`` the
part's tessellation as binary STL bytes in mm about ``offset`` (3,) mm, within
``deviation`` mm of the surface, ``self_checked`` whether its faces were checked for
crossing one another), or ``defect``, a sentence saying
what is wrong with the file. Lengths are OpenCASCADE's (millimetres, whatever unit
the file declares: the reader converts).

It runs apart (:func:`plumbob.formats.step.read_step` starts it) so that a crash of
the C++ library on a hostile file costs one line, not the process, and so that its
memory and time can be bounded. It imports nothing of plumbob.
"""

from __future__ import annotations

import json
import os
import pickle
import sys
import tempfile

#: the integration's relative tolerance (``BRepGProp.VolumeProperties_s``'s ``Eps``)
GPROP_EPS = 1e-12
#: parts with more faces than this are not checked for faces crossing each other
#: (:func:`_crosses_itself`: a few seconds at this size)
SELF_CHECK_FACES = 500


def _name(label) -> str | None:
    from OCP.TDataStd import TDataStd_Name

    attr = TDataStd_Name()
    if label.FindAttribute(TDataStd_Name.GetID_s(), attr):
        text = attr.Get().ToExtString()
        return text or None
    return None


def _instances(label, location, name: str | None, depth: int, out: list) -> None:
    """Every part instance under ``label``, placed: (name, located shape)."""
    from OCP.OCP.collections import Sequence_TDF_Label
    from OCP.TDF import TDF_Label
    from OCP.XCAFDoc import XCAFDoc_ShapeTool

    if depth > 64:
        raise ValueError("its assembly is nested more than 64 deep")
    if XCAFDoc_ShapeTool.IsAssembly_s(label):
        components = Sequence_TDF_Label()
        XCAFDoc_ShapeTool.GetComponents_s(label, components, False)
        for i in range(1, components.Length() + 1):
            component = components.Value(i)
            referred = TDF_Label()
            XCAFDoc_ShapeTool.GetReferredShape_s(component, referred)
            place = location.Multiplied(XCAFDoc_ShapeTool.GetLocation_s(component))
            _instances(referred, place, _name(referred) or _name(component), depth + 1, out)
        return
    shape = XCAFDoc_ShapeTool.GetShape_s(label)
    out.append((name or _name(label), shape.Located(location.Multiplied(shape.Location()))))


def _count(shape, kind) -> int:
    from OCP.TopExp import TopExp_Explorer

    explorer, n = TopExp_Explorer(shape, kind), 0
    while explorer.More():
        n += 1
        explorer.Next()
    return n


def _solid_defect(shape) -> str | None:
    """Why ``shape`` is not one valid closed solid, or None."""
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.TopAbs import TopAbs_FACE, TopAbs_SHELL, TopAbs_SOLID

    if _count(shape, TopAbs_SOLID) == 0:
        if _count(shape, TopAbs_SHELL):
            return "holds an open shell, not a closed solid"
        if _count(shape, TopAbs_FACE):
            return "holds faces only, not a closed solid"
        return "holds no solid (wires or points only)"
    if not BRepCheck_Analyzer(shape).IsValid():
        return "holds an invalid solid: self-intersecting or not closed (OpenCASCADE's check)"
    return None


def _crosses_itself(shape) -> bool | None:
    """Whether the solid's faces cross one another (OpenCASCADE's Boolean self-interference
    check, ``BRepAlgoAPI_Check``), which :func:`_solid_defect`'s topology check does not
    see: a cube with a corner pushed through its opposite face is valid to it. None when
    the solid has over :data:`SELF_CHECK_FACES` faces: the check grows with the square of
    the faces (0.2 s at 100, 3 s at 400, 70 s at 1,600), so it is left out, and said."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Check
    from OCP.TopAbs import TopAbs_FACE

    if _count(shape, TopAbs_FACE) > SELF_CHECK_FACES:
        return None
    return not BRepAlgoAPI_Check(shape, False, True).IsValid()


def _planar(shape) -> bool:
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_Plane
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        if BRepAdaptor_Surface(TopoDS.Face(explorer.Current())).GetType() != GeomAbs_Plane:
            return False
        explorer.Next()
    return True


def _part(name: str | None, shape, deviation: float) -> dict:
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib
    from OCP.BRepGProp import BRepGProp
    from OCP.BRepMesh import BRepMesh_IncrementalMesh
    from OCP.gp import gp_Trsf, gp_Vec
    from OCP.GProp import GProp_GProps
    from OCP.StlAPI import StlAPI_Writer
    from OCP.TopLoc import TopLoc_Location

    props = GProp_GProps()
    error = BRepGProp.VolumeProperties_s(shape, props, GPROP_EPS, True)
    c = props.CentreOfMass()
    m = props.MatrixOfInertia()
    inertia = [[m.Value(i, j) for j in (1, 2, 3)] for i in (1, 2, 3)]
    box = Bnd_Box()
    BRepBndLib.Add_s(shape, box)
    lo, hi = box.CornerMin(), box.CornerMax()
    size = ((hi.X() - lo.X()) ** 2 + (hi.Y() - lo.Y()) ** 2 + (hi.Z() - lo.Z()) ** 2) ** 0.5
    # the linear deviation rules; a finer angle than 0.5 rad costs minutes on a torus
    BRepMesh_IncrementalMesh(shape, deviation * size, False, 0.5, False)
    # written about the box's centre, so float32 STL coordinates lose nothing to the
    # part's distance from the origin (the centre is added back in float64)
    middle = ((lo.X() + hi.X()) / 2, (lo.Y() + hi.Y()) / 2, (lo.Z() + hi.Z()) / 2)
    shift = gp_Trsf()
    shift.SetTranslation(gp_Vec(-middle[0], -middle[1], -middle[2]))
    with tempfile.TemporaryDirectory() as folder:
        stl = os.path.join(folder, "part.stl")
        writer = StlAPI_Writer()
        writer.ASCIIMode = False
        if not writer.Write(shape.Moved(TopLoc_Location(shift)), stl):
            raise ValueError("OpenCASCADE could not tessellate a part")
        with open(stl, "rb") as f:
            data = f.read()
    return {"name": name, "volume": props.Mass(), "centre": (c.X(), c.Y(), c.Z()),
            "inertia": inertia, "error": abs(error), "planar": _planar(shape),
            "deviation": deviation * size, "stl": data, "offset": middle}


def read(path: str, deviation: float) -> dict:
    """The parts of the STEP (or IGES, BREP) file ``path``, or its defect."""
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.OCP.collections import Sequence_TDF_Label
    from OCP.TCollection import TCollection_ExtendedString
    from OCP.TDocStd import TDocStd_Document
    from OCP.TopLoc import TopLoc_Location
    from OCP.XCAFDoc import XCAFDoc_DocumentTool

    if path.lower().endswith(".brep"):  # OpenCASCADE's own format: one shape, no names
        from OCP.BRep import BRep_Builder
        from OCP.BRepTools import BRepTools
        from OCP.TopoDS import TopoDS_Shape

        shape = TopoDS_Shape()
        if not BRepTools.Read_s(shape, path, BRep_Builder()) or shape.IsNull():
            return {"defect": "OpenCASCADE cannot parse it as a BREP file"}
        return _parts([(os.path.splitext(os.path.basename(path))[0], shape)], deviation)
    if path.lower().endswith((".igs", ".iges")):
        from OCP.IGESCAFControl import IGESCAFControl_Reader as Reader
    else:
        from OCP.STEPCAFControl import STEPCAFControl_Reader as Reader
    reader = Reader()
    reader.SetNameMode(True)
    if reader.ReadFile(path) != IFSelect_RetDone:
        return {"defect": "OpenCASCADE cannot parse it (a syntax error, or not STEP)"}
    doc = TDocStd_Document(TCollection_ExtendedString("plumbob"))
    if not reader.Transfer(doc):
        return {"defect": "OpenCASCADE read it but found no shape to transfer"}
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    free = Sequence_TDF_Label()
    tool.GetFreeShapes(free)
    found: list = []
    for i in range(1, free.Length() + 1):
        label = free.Value(i)
        _instances(label, TopLoc_Location(), _name(label), 0, found)
    return _parts(found, deviation)


def _parts(found: list, deviation: float) -> dict:
    """Each (name, placed shape) checked and measured, or the first defect."""
    if not found:
        return {"defect": "holds no shape"}
    parts, checked = [], []
    for name, shape in found:
        defect = _solid_defect(shape)
        if defect is not None:
            return {"defect": f"part {name!r} {defect}" if name else defect}
        # instances of one part share its shape: checked once
        crosses = next((c for s, c in checked if s.IsPartner(shape)), "unchecked")
        if crosses == "unchecked":
            crosses = _crosses_itself(shape)
            checked.append((shape, crosses))
        if crosses:
            return {"defect": (f"part {name!r} " if name else "") + "holds a self-intersecting "
                    "solid: its faces cross one another (OpenCASCADE's self-interference "
                    "check); repair it in the CAD program"}
        part = _part(name, shape, deviation)
        part["self_checked"] = crosses is not None
        if not part["volume"] > 0:
            return {"defect": f"part {name!r} has no positive volume: a self-intersecting or "
                              "inside-out solid"}
        parts.append(part)
    return {"parts": parts}


def _answer(path: str, out: str, deviation: float) -> None:
    """Read ``path`` and write its result (or its defect) to ``out``."""
    try:
        result = read(path, deviation)
    except ValueError as error:
        result = {"defect": str(error)}
    with open(out, "wb") as f:
        pickle.dump(result, f)


def main() -> None:
    """``FILE OUT DEVIATION``: one read; ``--serve``: one read per line of standard input
    (``[FILE, OUT, DEVIATION]`` as JSON), answered ``done`` on standard output."""
    serving = sys.argv[1:] == ["--serve"]
    replies = os.fdopen(os.dup(1), "w") if serving else None
    # OpenCASCADE prints its statistics on the C stdout: keep them off the parent's pipe
    os.dup2(os.open(os.devnull, os.O_WRONLY), 1)
    if not serving:
        _answer(sys.argv[1], sys.argv[2], float(sys.argv[3]))
        return
    for line in sys.stdin:
        path, out, deviation = json.loads(line)
        _answer(path, out, float(deviation))
        replies.write("done\n")
        replies.flush()


if __name__ == "__main__":
    main()
