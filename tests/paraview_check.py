"""Opens a vorodec .pvd series in ParaView, visits every time step and saves a PNG of the last one.

Run with ParaView's pvbatch (not plain python), normally through tests/run_paraview_check.sh:
    pvbatch tests/paraview_check.py results/run/blocks.pvd out.png [cell_array]
    pvbatch tests/paraview_check.py results/run/damage.pvd out.png damage_density
The series may hold polygon data (.vtp: blocks, contacts, cracks) or image data (.vti: the damage
grid); ParaView must report the data set type the file extension promises.
cell_array defaults to displacement, id, type, state or damage_density, whichever the series has
first. Exits non-zero on any failure and prints the times it visited.
"""
import os
import sys
import xml.etree.ElementTree as ET


def fail(msg):
    print("paraview_check: FAIL: " + msg, flush=True)
    sys.exit(1)


EXPECTED_TYPE = {".vtp": "vtkPolyData", ".vti": "vtkImageData"}


def pvd_times(pvd):
    try:
        root = ET.parse(pvd).getroot()
    except (OSError, ET.ParseError) as e:
        fail("cannot parse %s: %s" % (pvd, e))
    if root.get("type") != "Collection":
        fail("%s is not a VTK Collection file" % pvd)
    times, exts = [], set()
    for ds in root.iter("DataSet"):
        f = os.path.join(os.path.dirname(pvd), ds.get("file", ""))
        if not os.path.isfile(f):
            fail("%s lists missing file %s" % (pvd, f))
        times.append(float(ds.get("timestep")))
        exts.add(os.path.splitext(f)[1])
    if len(exts) > 1:
        fail("%s mixes file types %r" % (pvd, sorted(exts)))
    return times, (exts.pop() if exts else "")


def main(argv):
    if len(argv) < 3:
        fail("usage: pvbatch paraview_check.py file.pvd out.png [cell_array]")
    pvd, png = os.path.abspath(argv[1]), os.path.abspath(argv[2])
    wanted = argv[3] if len(argv) > 3 else None
    expected, ext = pvd_times(pvd)
    if not expected:
        fail("%s lists no data sets" % pvd)

    from paraview import simple as pv  # noqa: E402  (only importable under pvbatch)

    reader = pv.PVDReader(FileName=pvd)
    tv = reader.TimestepValues
    times = [float(t) for t in tv] if hasattr(tv, "__len__") else [float(tv)]
    if sorted(times) != sorted(set(expected)):
        fail("ParaView reports times %r, the file lists %r" % (times, expected))

    visited = []
    for t in times:
        reader.UpdatePipeline(t)
        info = reader.GetDataInformation()
        ncells, npoints = info.GetNumberOfCells(), info.GetNumberOfPoints()
        vtk_info = getattr(info, "DataInformation", info)
        dtype = vtk_info.GetDataSetTypeAsString()
        print("paraview_check: t=%.17g %s cells=%d points=%d" % (t, dtype, ncells, npoints),
              flush=True)
        if ext in EXPECTED_TYPE and dtype != EXPECTED_TYPE[ext]:
            fail("a %s series reads as %s, expected %s" % (ext, dtype, EXPECTED_TYPE[ext]))
        if ext == ".vti" and ncells == 0:
            fail("image data without cells at t=%.17g" % t)
        visited.append(t)

    arrays = list(reader.CellData.keys())
    if wanted is None:
        preferred = [a for a in ("displacement", "id", "type", "state", "damage_density")
                     if a in arrays]
        if not preferred and not arrays:
            fail("no cell arrays in %s" % pvd)
        wanted = (preferred or arrays)[0]
    if wanted not in arrays:
        fail("cell array %r not found; have %r" % (wanted, arrays))

    last = times[-1]
    view = pv.CreateRenderView()
    view.ViewSize = [1000, 600]
    view.ViewTime = last
    view.InteractionMode = "2D"
    view.OrientationAxesVisibility = 0
    view.Background = [1.0, 1.0, 1.0]
    try:  # ParaView >= 5.10 uses a palette unless told otherwise
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    display = pv.Show(reader, view)
    # Edges only while they do not hide the colours.
    ncells_last = reader.GetDataInformation().GetNumberOfCells()
    display.SetRepresentationType("Surface With Edges" if ncells_last <= 1000 else "Surface")
    pv.ColorBy(display, ("CELLS", wanted))
    display.RescaleTransferFunctionToDataRange(True, False)
    display.SetScalarBarVisibility(view, True)
    bar = pv.GetScalarBar(pv.GetColorTransferFunction(wanted), view)
    bar.TitleColor = [0.0, 0.0, 0.0]
    bar.LabelColor = [0.0, 0.0, 0.0]
    pv.ResetCamera(view)
    pv.Render(view)
    pv.SaveScreenshot(png, view, ImageResolution=[1000, 600])
    if not os.path.isfile(png) or os.path.getsize(png) == 0:
        fail("no image written to " + png)

    print("paraview_check: times visited: " + " ".join("%.17g" % t for t in visited))
    print("paraview_check: coloured by cell array %r at t=%.17g -> %s" % (wanted, last, png))
    print("paraview_check: OK", flush=True)


if __name__ == "__main__":
    try:
        main(sys.argv)
    except SystemExit:
        raise
    except Exception as e:  # pvbatch may swallow tracebacks: report and exit non-zero
        import traceback

        traceback.print_exc()
        fail("%s: %s" % (type(e).__name__, e))
