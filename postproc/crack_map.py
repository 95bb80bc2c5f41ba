#!/usr/bin/python3
"""Draws the blocks and cracks of one frame of a vorodec ParaView series as a PNG.

Usage: postproc/crack_map.py results/ucs_marble [-o out.png] [--frame N] [--shade ARRAY] [--by-class]
       postproc/crack_map.py results/ucs_marble/blocks.pvd ...

Reads blocks.pvd and cracks.pvd of the folder (or of its vtk/ subfolder) and draws the last frame
(or frame N, negative counts from the end): blocks as light grey polygons with thin edges, cracks red = tensile,
blue = shear. --shade failed_fraction (or any other scalar block cell array) shades the blocks in
greys by that array instead, with a colour bar: failed_fraction is the fraction of each block's
initial bonded contacts that have failed. --by-class colours the cracks of a grain-based specimen
by class (intergranular/transgranular x tensile/shear) on blocks tinted by mineral. Only matplotlib and VTK's XML reader are used, so no X
server is needed. Default output: <folder>/crack_map.png.

Needs Debian's /usr/bin/python3 with python3-vtk9, python3-numpy and python3-matplotlib.
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader  # noqa: E402

CRACK_STYLE = {1: ("tensile", "red"), 2: ("shear", "blue")}
# Grain-based specimens: the cracks' `class` array (--by-class).
CLASS_STYLE = {1: ("intergranular tensile", "red"), 2: ("intergranular shear", "blue"),
               3: ("transgranular tensile", "orange"), 4: ("transgranular shear", "green")}


def read_pvd(pvd):
    """Returns [(time, absolute .vtp path)] sorted by time."""
    root = ET.parse(pvd).getroot()
    base = os.path.dirname(os.path.abspath(pvd))
    entries = [(float(d.get("timestep")), os.path.join(base, d.get("file")))
               for d in root.iter("DataSet")]
    if not entries:
        raise ValueError("%s lists no data sets" % pvd)
    return sorted(entries, key=lambda e: e[0])


def read_vtp(path):
    if not os.path.isfile(path):
        raise ValueError("missing %s" % path)
    r = vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    if r.GetErrorCode() != 0:
        raise ValueError("cannot read %s" % path)
    return r.GetOutput()


def points_xy(pd):
    if pd.GetNumberOfPoints() == 0:
        return np.zeros((0, 2))
    return vtk_to_numpy(pd.GetPoints().GetData())[:, :2]


def cells(cell_array):
    """Point-id lists of a vtkCellArray (VTK 9 offsets + connectivity layout)."""
    if cell_array.GetNumberOfCells() == 0:
        return []
    off = vtk_to_numpy(cell_array.GetOffsetsArray())
    conn = vtk_to_numpy(cell_array.GetConnectivityArray())
    return [conn[off[i]:off[i + 1]] for i in range(len(off) - 1)]


def cell_array(pd, name):
    a = pd.GetCellData().GetArray(name)
    return None if a is None else vtk_to_numpy(a)


def draw(folder, frame, out, shade=None, by_class=False):
    blocks = read_pvd(os.path.join(folder, "blocks.pvd"))
    t, blocks_vtp = blocks[frame]
    cracks_vtp = None
    cracks_pvd = os.path.join(folder, "cracks.pvd")
    if os.path.isfile(cracks_pvd):
        # The cracks frame with the same time as the blocks frame, else the latest not after it.
        cands = [e for e in read_pvd(cracks_pvd) if e[0] <= t] or []
        cracks_vtp = cands[-1][1] if cands else None

    bpd = read_vtp(blocks_vtp)
    bxy = points_xy(bpd)
    polys = [bxy[ids] for ids in cells(bpd.GetPolys())]
    nblocks = len(polys)

    # Figure shaped like the specimen, so a tall UCS sample is not lost in white space.
    aspect = 1.0
    if len(bxy):
        ext = bxy.max(axis=0) - bxy.min(axis=0)
        aspect = float(np.clip(ext[1] / ext[0], 0.3, 3.0)) if ext[0] > 0 else 1.0
    w, h = (7.5, 7.5 * aspect) if aspect <= 1.0 else (7.5 / aspect, 7.5)
    fig, ax = plt.subplots(figsize=(w + 1.3, h + 1.0), dpi=200)
    edge_lw = float(np.clip(8.0 / np.sqrt(max(nblocks, 1)), 0.1, 0.8))
    if shade is None and not by_class:
        ax.add_collection(PolyCollection(polys, facecolors="0.85", edgecolors="0.45",
                                         linewidths=edge_lw))
    elif shade is not None:  # --by-class alone tints the blocks by mineral below
        values = cell_array(bpd, shade)
        if values is None or values.ndim != 1:
            raise ValueError("%s has no scalar block cell array %r" % (blocks_vtp, shade))
        pc = PolyCollection(polys, array=values, cmap="Greys", edgecolors="0.55",
                            linewidths=edge_lw)
        pc.set_clim(0.0, max(float(values.max()), 1e-12))
        ax.add_collection(pc)
        fig.colorbar(pc, ax=ax, shrink=0.6, pad=0.02, label=shade)

    style = CLASS_STYLE if by_class else CRACK_STYLE
    if by_class:
        mineral = cell_array(bpd, "mineral")
        if mineral is None:
            raise ValueError("%s has no 'mineral' array: not a grain-based specimen" % blocks_vtp)
        # Blocks in pale tones by mineral (platens, -1, in grey), so the cracks stand out.
        tones = ["#f3e6c8", "#dfe9f3", "#e8dcef", "#dcefdc", "#f3dcdc", "#ececec"]
        ax.add_collection(PolyCollection(
            polys, facecolors=[tones[m % (len(tones) - 1)] if m >= 0 else tones[-1]
                               for m in mineral],
            edgecolors="0.6", linewidths=edge_lw))
    counts = {}
    if cracks_vtp is not None:
        cpd = read_vtp(cracks_vtp)
        cxy = points_xy(cpd)
        segs = [cxy[ids] for ids in cells(cpd.GetLines())]
        array = "class" if by_class else "type"
        types = cell_array(cpd, array)
        if segs and types is None:
            raise ValueError("%s has no '%s' cell array" % (cracks_vtp, array))
        crack_lw = float(np.clip(4.0 * edge_lw, 0.6, 2.0))
        for code, (label, colour) in style.items():
            sel = [s for s, ty in zip(segs, types if types is not None else []) if ty == code]
            counts[label] = len(sel)
            if sel:
                ax.add_collection(LineCollection(sel, colors=colour, linewidths=crack_lw, zorder=3))

    if len(bxy):
        lo, hi = bxy.min(axis=0), bxy.max(axis=0)
        pad = 0.02 * float(max(hi - lo))
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    handles = [Line2D([], [], color=c, lw=2, label="%s (%d)" % (l, counts.get(l, 0)))
               for l, c in style.values()]
    ax.legend(handles=handles, loc="upper right", fontsize=8, framealpha=0.9)
    name = os.path.basename(os.path.abspath(folder))
    if name == "vtk":  # the series folder of a run: name the run
        name = os.path.basename(os.path.dirname(os.path.abspath(folder)))
    ax.set_title("%s: %d blocks, t = %.6g s" % (name, nblocks, t))
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)
    return t, nblocks, counts


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("series", help="result folder (or its vtk/ folder) holding blocks.pvd and "
                   "cracks.pvd, or blocks.pvd")
    p.add_argument("-o", "--output", help="PNG to write (default: <folder>/crack_map.png)")
    p.add_argument("--frame", type=int, default=-1, help="frame index, negative from the end")
    p.add_argument("--shade", metavar="ARRAY",
                   help="shade blocks by this block cell array, e.g. failed_fraction")
    p.add_argument("--by-class", action="store_true",
                   help="colour cracks by grain class (grain-based specimens)")
    args = p.parse_args(argv)
    folder = args.series if os.path.isdir(args.series) else os.path.dirname(os.path.abspath(args.series))
    out = args.output or os.path.join(folder, "crack_map.png")
    # A run's results folder keeps its series in vtk/.
    if not os.path.isfile(os.path.join(folder, "blocks.pvd")) and os.path.isfile(
            os.path.join(folder, "vtk", "blocks.pvd")):
        folder = os.path.join(folder, "vtk")
    try:
        t, nblocks, counts = draw(folder, args.frame, out, args.shade, args.by_class)
    except (OSError, ValueError, IndexError, ET.ParseError) as e:
        print("crack_map: %s" % e, file=sys.stderr)
        return 1
    print("crack_map: wrote %s (t = %.17g s, %d blocks, %s)" % (
        out, t, nblocks, ", ".join("%d %s cracks" % (n, k) for k, n in counts.items()) or "no cracks"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
