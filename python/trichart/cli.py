"""The `trichart` command: run TriChart stages on mesh files from the shell."""
import argparse
import json
import os
import re
import shutil
import sys
import time


class ProgressBar:
    """A one-line progress bar on stderr (plain lines when stderr is not a terminal)."""

    def __init__(self, stream=sys.stderr):
        self.stream = stream
        self.tty = stream.isatty()
        self.label = None
        self.last = -1

    def __call__(self, label, fraction):
        percent = int(100 * fraction)
        if label != self.label:
            if self.label is not None and self.tty:
                self.stream.write("\n")
            self.label, self.last = label, -1
        if self.tty:
            filled = percent * 30 // 100
            self.stream.write(f"\r{label:<10} [{'#' * filled}{'.' * (30 - filled)}] {percent:3d}%")
            self.stream.flush()
        elif percent // 25 != self.last // 25 or percent == 100 and self.last != 100:
            self.stream.write(f"{label}: {percent}%\n")
        self.last = percent
        return True

    def close(self):
        if self.tty and self.label is not None:
            self.stream.write("\n")


_UNITS = {"": 1, "K": 2 ** 10, "M": 2 ** 20, "G": 2 ** 30, "T": 2 ** 40}


def memory_size(text):
    """Bytes of a --max-memory value: '8G', '512M', '1.5g', '64MiB', '1000000' (bytes)."""
    match = re.fullmatch(r"\s*(\d+(?:\.\d*)?)\s*([kmgtKMGT]?)(?:i?[bB])?\s*", text)
    if not match:
        raise argparse.ArgumentTypeError(
            f"'{text}' is no memory size: give bytes, or a number with K, M, G or T (8G, 512M)")
    return int(float(match.group(1)) * _UNITS[match.group(2).upper()])


def _needs_display(args):
    return args.command == "build" and args.stages and not args.no_image


def _reexec_under_xvfb():
    """Rendering needs an X display (Debian's VTK has no offscreen-only back end): when there
    is none, run this same command again under xvfb-run."""
    xvfb = shutil.which("xvfb-run")
    if not xvfb or os.environ.get("TRICHART_UNDER_XVFB"):
        return False
    env = dict(os.environ, TRICHART_UNDER_XVFB="1")
    os.execvpe(xvfb, [xvfb, "-a", "-s", "-screen 0 1280x1024x24 -noreset", sys.executable, "-m",
                      "trichart"] + sys.argv[1:], env)
    return True


def cmd_info(_args):
    import trichart
    from trichart import _config
    from vtkmodules.vtkCommonCore import vtkVersion

    print(f"TriChart {trichart.__version__} ({_config.BUILD_TYPE} build)")
    print(f"VTK {vtkVersion.GetVTKVersion()} (built against {_config.VTK_VERSION})")
    print(f"ParaView {_config.PARAVIEW_VERSION or 'not found at build time'}")
    print(f"Python {sys.version.split()[0]} ({sys.executable})")
    print(f"Python package {os.path.dirname(trichart.__file__)}")
    print(f"ParaView plugin {trichart.plugin_path() or 'not built'}")
    return 0


def _finest_level(atlas):
    """The largest d_max over the charts of an atlas multiblock."""
    from .TriChartIO import tcArrayNames

    levels = atlas.GetBlock(0).GetColumnByName(tcArrayNames.MaxLevel())
    return max(levels.GetValue(c) for c in range(levels.GetNumberOfTuples()))


def _build_options(args):
    """pipeline.build's keyword options from the command line of `trichart build`."""
    return {"stages": args.stages, "image": not args.no_image,
            "cluster_options": {"number_of_clusters": args.clusters},
            "feature_options": {"crease_angle": args.crease_angle,
                                "crease_line_angle": args.crease_lines,
                                "seam_lines": not args.no_seam_lines,
                                "skin_lines": args.skin_lines},
            "base_options": {"target_faces": args.base_faces, "max_error": args.max_error},
            "geometry_options": {"max_level": args.max_level, "sample_budget": args.budget,
                                 "error_target": args.error_target,
                                 "stretch_iterations": args.stretch_iterations,
                                 "fit_samples": not args.no_fit,
                                 "keep_appearance": not args.no_appearance},
            "prepare_options": _repair_options(args),
            "read_options": _read_options(args)}


def _read_options(args):
    """read_mesh's options from the command line (a terrain raster's vertical scale)."""
    return {"vertical_scale": args.vertical_scale}


def _add_read_options(parser):
    parser.add_argument("--vertical-scale", type=float, default=1.0, metavar="S",
                        help="a terrain raster (.tif, .asc, .pgm, ...): multiply its heights "
                             "by S (default 1)")


def _scene_lines(mesh):
    """What a scene file held beyond its surfaces (bones, animations): the lines of the reader's
    report (field array ReaderReport, a line per value) after the file and the counts, other
    than the array lines."""
    from .TriChartIO import tcArrayNames

    field = mesh.GetFieldData().GetAbstractArray(tcArrayNames.ReaderReport())
    lines = [field.GetValue(i) for i in range(field.GetNumberOfValues())][2:] if field else []
    return [line for line in lines if not line.startswith(("point array", "cell array"))]


def _input_triangles(mesh):
    """The triangles of the mesh as read: each polygon counts as its fan."""
    import numpy
    from vtkmodules.util.numpy_support import vtk_to_numpy

    sides = numpy.diff(vtk_to_numpy(mesh.GetPolys().GetOffsetsArray()).astype(numpy.int64))
    return int((sides - 2).clip(min=0).sum())


def _build_figures(args, result, seconds, peak):
    """Every figure the build summary prints, by name; `peak`: the build's peak memory."""
    surface = result["surface"]
    size = os.path.getsize(result["files"]["atlas"])
    triangles = _input_triangles(result["mesh"])
    return {"mesh": str(args.mesh), "points": surface.GetNumberOfPoints(),
            "triangles": surface.GetNumberOfCells(), "input_triangles": triangles,
            "feature_lines": result["feature_lines"].GetNumberOfCells(),
            "corners": result["corners"].GetNumberOfPoints(),
            "base_triangles": result["base_complex"].GetNumberOfPolys(),
            "charts": result["atlas"].GetBlock(0).GetNumberOfRows(),
            "finest_level": _finest_level(result["atlas"]), "seconds": seconds,
            "stage_seconds": result["seconds"], "atlas_bytes": size,
            "bytes_per_input_triangle": size / max(triangles, 1),
            "retried": result["retried"], "read": _scene_lines(result["mesh"]),
            "prepared": result["report"].splitlines(), "files": result["files"],
            "memory": {"peak": peak, **result["memory"]}}


def _print_build_summary(f):
    """The counts of every stage, the seconds per stage, the atlas size, what was read and
    repaired, the files written and the memory against its estimate."""
    print(f"{f['mesh']}: {f['points']} points, {f['triangles']} triangles, "
          f"{f['feature_lines']} feature lines, {f['corners']} corners, "
          f"{f['base_triangles']} base triangles, {f['charts']} charts up to level "
          f"{f['finest_level']} ({f['seconds']:.2f} s)")
    print("  seconds per stage: " + ", ".join(f"{name} {value:.2f}"
                                              for name, value in f["stage_seconds"].items()))
    print(f"  atlas: {f['atlas_bytes'] / 1e6:.2f} MB, {f['bytes_per_input_triangle']:.1f} bytes "
          f"per input triangle")
    if f["retried"]:
        print(f"  note: {f['retried']}")
    for line in f["read"]:
        print(f"  read: {line}")
    for line in f["prepared"]:
        print(f"  prepared: {line}")
    for name, path in f["files"].items():
        print(f"  wrote {name}: {path}")
    memory = f["memory"]
    print(f"  memory: peak {memory['peak'] / 2 ** 20:.0f} MB resident, estimated "
          f"{memory['estimate'] / 2 ** 20:.0f} MB above the {memory['start'] / 2 ** 20:.0f} MB "
          f"held at the start")


def cmd_build(args):
    from .pipeline import build, resident_memory, set_max_threads

    set_max_threads(args.threads)
    bar = None if args.quiet else ProgressBar()
    start = time.perf_counter()
    try:
        result = build(args.mesh, args.output, progress=bar, max_memory=args.max_memory,
                       **_build_options(args))
    finally:
        if bar:
            bar.close()
    # VmHWM (reset as the build starts), not getrusage's ru_maxrss: that one keeps the peak of
    # the process this one was forked from across exec (a test runner's, a shell's). Taken
    # before the figures, whose modules (numpy) are no part of the build.
    peak = resident_memory("VmHWM")
    figures = _build_figures(args, result, time.perf_counter() - start, peak)
    if args.json:
        print(json.dumps(figures, indent=2))
    else:
        _print_build_summary(figures)
    return 0


def cmd_mesh(args):
    from .pipeline import check_mesh_file_name, read_atlas, rebuild, write_mesh

    check_mesh_file_name(args.output)
    atlas = read_atlas(args.atlas)
    mesh = rebuild(atlas, level=args.level)
    posed = ""
    if args.time is not None:
        from .pipeline import pose
        mesh = pose(mesh, args.time, animation=args.animation)
        posed = f", posed at {args.time:g} s"
    print(f"{args.atlas} at level {args.level}: {mesh.GetNumberOfPoints()} points, "
          f"{mesh.GetNumberOfPolys()} triangles{posed}")
    print(f"wrote {write_mesh(mesh, args.output)}")
    return 0


def cmd_pose(args):
    """The animations and time steps of a skinned scene or a sequence; with --time, the mesh
    (and --skeleton, the skeleton) posed at that time."""
    from .pipeline import (animation_names, check_mesh_file_name, read_mesh, read_skeleton,
                           time_steps, write_mesh)

    for path in (args.output, args.skeleton):
        if path:
            check_mesh_file_name(path)
    names = animation_names(args.source)
    steps = time_steps(args.source, animation=args.animation)
    for index, name in enumerate(names):
        print(f"animation {index}: {name}")
    if steps:
        print(f"{len(steps)} time steps, {steps[0]:g} to {steps[-1]:g} s")
    else:
        print("no time steps: the file does not move")
    if args.time is None:
        if args.output or args.skeleton:
            raise SystemExit("trichart: error: --time T says when to pose (see the time steps above)")
        return 0
    if args.output:
        mesh = read_mesh(args.source, time=args.time, animation=args.animation)
        print(f"wrote {write_mesh(mesh, args.output)} ({mesh.GetNumberOfPoints()} points, "
              f"posed at {args.time:g} s)")
    if args.skeleton:
        skeleton = read_skeleton(args.source, time=args.time, animation=args.animation)
        if skeleton.GetNumberOfPoints() == 0:
            raise SystemExit(f"trichart: error: {args.source} has no skeleton")
        print(f"wrote {write_mesh(skeleton, args.skeleton)} ({skeleton.GetNumberOfPoints()} joints)")
    return 0


def cmd_export(args):
    from .pipeline import check_gltf_file_name, export_gltf, read_atlas

    check_gltf_file_name(args.output)
    atlas = read_atlas(args.atlas)
    bar = None if args.quiet else ProgressBar()
    try:
        lods = export_gltf(atlas, args.output, progress=bar, chain=CHAINS.index(args.chain),
                           layout=LAYOUTS.index(args.layout), error_ratio=args.error_ratio,
                           max_lods=args.max_lods, error_pixels=args.error_pixels,
                           viewport_height=args.viewport_height)
    finally:
        if bar:
            bar.close()
    print(f"{'LOD':>4} {'triangles':>10} {'error/diag':>11} {'coverage':>9}")
    for k, lod in enumerate(lods):
        print(f"{k:>4} {lod['triangles']:>10} {100 * lod['error_fraction']:>10.4f}% "
              f"{lod['screen_coverage']:>9.4f}")
    print(f"wrote {os.path.abspath(args.output)} ({os.path.getsize(args.output)} bytes, "
          f"{len(lods)} LODs, {args.layout})")
    return 0


def _bounds_mismatch(mesh, reference):
    """Why `mesh` (an atlas's finest level) and `reference` do not look like one surface: their
    bounding boxes' diagonals or centres more than 10% of the reference's diagonal apart; ""
    when they agree."""
    import numpy

    a, b = numpy.array(mesh.GetBounds()), numpy.array(reference.GetBounds())
    size_a, size_b = a[1::2] - a[::2], b[1::2] - b[::2]
    diagonal = float(numpy.linalg.norm(size_b)) or 1.0
    centre = float(numpy.linalg.norm((a[1::2] + a[::2] - b[1::2] - b[::2]) / 2)) / diagonal
    size = abs(float(numpy.linalg.norm(size_a)) - diagonal) / diagonal
    if centre > 0.1 or size > 0.1:
        return (f"the atlas and the mesh do not look like one surface: their bounding boxes' "
                f"centres are {100 * centre:.0f}% of the diagonal apart and their diagonals "
                f"differ by {100 * size:.0f}% (was the atlas built from this mesh?)")
    return ""


def _eval_figures(args):
    """Every level's counts and errors against the prepared mesh, and a mismatch warning."""
    from .pipeline import prepare, read_atlas, read_mesh, rebuild, simplify_qem, surface_distance

    reference, _ = prepare(read_mesh(args.mesh, **_read_options(args)))
    atlas = read_atlas(args.atlas)
    figures = {"atlas": str(args.atlas), "mesh": str(args.mesh),
               "triangles": reference.GetNumberOfPolys(), "levels": [], "warning": ""}
    for level in range(_finest_level(atlas) + 1):
        mesh = rebuild(atlas, level=level)
        _, f = surface_distance(mesh, reference, samples_per_mesh=args.samples)
        diagonal = f["diagonal"] or 1.0
        row = {"level": level, "points": mesh.GetNumberOfPoints(),
               "triangles": mesh.GetNumberOfPolys(), "hausdorff": f["hausdorff"], "rms": f["rms"],
               "mean": f["mean"], "diagonal": f["diagonal"],
               "hausdorff_fraction": f["hausdorff"] / diagonal,
               "rms_fraction": f["rms"] / diagonal, "qem": None}
        if row["triangles"] < figures["triangles"]:  # the peer at the same count
            peer = simplify_qem(reference, row["triangles"])
            _, q = surface_distance(peer, reference, samples_per_mesh=args.samples)
            row["qem"] = {"triangles": peer.GetNumberOfPolys(),
                          "hausdorff_fraction": q["hausdorff"] / diagonal,
                          "rms_fraction": q["rms"] / diagonal}
        figures["levels"].append(row)
    figures["warning"] = _bounds_mismatch(mesh, reference)
    return figures


def _print_eval(figures):
    print(f"{figures['atlas']} against {figures['mesh']} ({figures['triangles']} triangles)")
    print(f"{'level':>5} {'points':>9} {'triangles':>10} {'Hausdorff':>12} {'RMS':>12} "
          f"{'Hausdorff/diag':>15} {'RMS/diag':>10} {'QEM H/diag':>11} {'H/QEM':>6}")
    for row in figures["levels"]:
        qem = row["qem"]
        peer = (f"{100 * qem['hausdorff_fraction']:>10.4f}% "
                f"{row['hausdorff_fraction'] / qem['hausdorff_fraction']:>6.2f}"
                if qem and qem["hausdorff_fraction"] > 0 else f"{'-':>11} {'-':>6}")
        print(f"{row['level']:>5} {row['points']:>9} {row['triangles']:>10} "
              f"{row['hausdorff']:>12.6g} {row['rms']:>12.6g} "
              f"{100 * row['hausdorff_fraction']:>14.4f}% {100 * row['rms_fraction']:>9.4f}% "
              f"{peer}")


def _plot_eval(figures, path):
    """Hausdorff and RMS against triangles, one point per level, log-log, as a PNG."""
    import matplotlib

    matplotlib.use("Agg")  # no display needed
    from matplotlib import pyplot

    rows = figures["levels"]
    triangles = [row["triangles"] for row in rows]
    figure, axes = pyplot.subplots(figsize=(7, 4.5), dpi=120)
    axes.loglog(triangles, [100 * r["hausdorff_fraction"] for r in rows], "o-", label="Hausdorff")
    axes.loglog(triangles, [100 * r["rms_fraction"] for r in rows], "s--", label="RMS")
    peers = [r["qem"] for r in rows if r["qem"] and r["qem"]["hausdorff_fraction"] > 0]
    if peers:
        axes.loglog([q["triangles"] for q in peers], [100 * q["hausdorff_fraction"] for q in peers],
                    "^:", color="grey", label="meshopt_simplify, Hausdorff")
    for row in rows:
        axes.annotate(f"L{row['level']}", (row["triangles"], 100 * row["hausdorff_fraction"]),
                      textcoords="offset points", xytext=(4, 4), fontsize=8)
    axes.set_xlabel("triangles")
    axes.set_ylabel("error, % of the diagonal")
    axes.set_title(f"{os.path.basename(figures['atlas'])} against "
                   f"{os.path.basename(figures['mesh'])}")
    axes.grid(True, which="both", alpha=0.3)
    axes.legend()
    figure.tight_layout()
    folder = os.path.dirname(os.path.abspath(path))
    temporary = os.path.join(folder, f".tmp-{os.getpid()}-{os.path.basename(path)}")
    try:
        figure.savefig(temporary, format="png")
        os.replace(temporary, path)
    finally:
        pyplot.close(figure)
        if os.path.exists(temporary):
            os.unlink(temporary)


def _frame_figures(args):
    """The finest level of a skinned atlas posed at N times evenly over the animation (its
    rest pose first) against the source posed alike: the Hausdorff distance per frame."""
    from .TriChartIO import tcArrayNames
    from .pipeline import (TriChartError, pose, prepare, read_atlas, read_frames, rebuild,
                           surface_distance, time_steps)

    atlas = read_atlas(args.atlas)
    finest = rebuild(atlas)
    if finest.GetFieldData().GetAbstractArray(tcArrayNames.Rig()) is None:
        raise TriChartError(f"{args.atlas} is not skinned: --frames poses a skinned atlas")
    steps = time_steps(args.mesh, animation=args.animation)
    if not steps:
        raise TriChartError(f"{args.mesh} has no animation to pose at --frames")
    frames = [None] + [steps[0] + (steps[-1] - steps[0]) * k / max(1, args.frames - 1)
                       for k in range(args.frames)]
    rows = []
    for t, source in zip(frames, read_frames(args.mesh, frames, animation=args.animation)):
        reference, _ = prepare(source)
        mesh = finest if t is None else pose(finest, t, animation=args.animation)
        _, f = surface_distance(mesh, reference, samples_per_mesh=args.samples)
        rows.append({"time": t, "hausdorff": f["hausdorff"], "diagonal": f["diagonal"],
                     "hausdorff_fraction": f["hausdorff"] / (f["diagonal"] or 1.0)})
    return {"atlas": str(args.atlas), "mesh": str(args.mesh), "rest": rows[0],
            "frames": rows[1:],
            "largest_ratio_to_rest": max(r["hausdorff_fraction"] for r in rows[1:]) /
            (rows[0]["hausdorff_fraction"] or 1.0)}


def _print_frames(figures):
    print(f"{figures['atlas']} posed against {figures['mesh']} (finest level)")
    print(f"{'time':>10} {'Hausdorff':>12} {'Hausdorff/diag':>15}")
    for row in [figures["rest"]] + figures["frames"]:
        when = "rest" if row["time"] is None else f"{row['time']:.4g} s"
        print(f"{when:>10} {row['hausdorff']:>12.6g} {100 * row['hausdorff_fraction']:>14.4f}%")
    print(f"largest frame / rest: {figures['largest_ratio_to_rest']:.3f}")


def cmd_eval(args):
    from .pipeline import TriChartError

    if args.frames:
        figures = _frame_figures(args)
        if args.json:
            print(json.dumps(figures, indent=2))
        else:
            _print_frames(figures)
        return 0
    if args.plot and not args.plot.lower().endswith(".png"):
        raise TriChartError(f"cannot write '{args.plot}': --plot writes a PNG, name it .png")
    figures = _eval_figures(args)
    if args.json:
        print(json.dumps(figures, indent=2))
    else:
        _print_eval(figures)
    if figures["warning"]:
        print(f"trichart: warning: {figures['warning']}", file=sys.stderr)
    if args.plot:
        _plot_eval(figures, args.plot)
        if not args.json:
            print(f"wrote {os.path.abspath(args.plot)}")
    return 0


def cmd_prepare(args):
    from .pipeline import check_mesh_file_name, prepare, read_mesh, write_mesh

    check_mesh_file_name(args.output)
    clean, report = prepare(read_mesh(args.mesh, **_read_options(args)),
                            merge_tolerance=args.merge_tolerance,
                            **_repair_options(args))
    print(report.strip() or "nothing to change")
    print(f"wrote {write_mesh(clean, args.output)}")
    return 0


def _repair_options(args):
    """The preparation's repairs from the command line, shared by build and prepare."""
    return {"fill_holes": args.fill_holes, "max_hole_edges": args.max_hole_edges,
            "split_non_manifold": args.split_non_manifold, "remove_slivers": args.remove_slivers,
            "drop_non_orientable": args.drop_non_orientable,
            "min_component_triangles": args.min_component_triangles,
            "keep_largest_component": args.keep_largest_component}


class _Defaults:
    """The filters whose property defaults and ranges the options take (one home for each)."""

    def __init__(self):
        from .TriChartBaseComplex import tcBaseComplex
        from .TriChartFeatures import tcFeatureRefinement, tcSpectralClustering
        from .TriChartGeometryImages import (tcGeometryImageMesh, tcGeometryImages,
                                             tcSurfaceDistance)
        from .TriChartIO import tcGLTFWriter
        from .TriChartPreparation import tcMeshPreparation

        self.preparation = tcMeshPreparation()
        self.clusters = tcSpectralClustering()
        self.features = tcFeatureRefinement()
        self.base = tcBaseComplex()
        self.images = tcGeometryImages()
        self.rebuild = tcGeometryImageMesh()
        self.distance = tcSurfaceDistance()
        self.gltf = tcGLTFWriter()


def _add_repair_options(parser, d):
    """The preparation's repairs, shared by build and prepare."""
    prep = d.preparation
    parser.add_argument("--split-non-manifold", action="store_true",
                        help="split non-manifold edges and vertices in the preparation")
    parser.add_argument("--fill-holes", action="store_true",
                        help="close the mesh's holes (up to --max-hole-edges boundary edges "
                             "each) with faired patches: the pipeline needs closed surfaces, "
                             "scans often are not")
    parser.add_argument("--max-hole-edges", type=int, default=prep.GetMaxHoleEdges(),
                        help=f"largest hole --fill-holes closes, in boundary edges (default "
                             f"{prep.GetMaxHoleEdges()}; 0: any size)")
    parser.add_argument("--remove-slivers", action="store_true",
                        help=f"collapse needles and flip caps (angles over "
                             f"{prep.GetSliverAngle():g} degrees, sides "
                             f"{prep.GetSliverEdgeRatio():g} times the shortest) in the "
                             "preparation: scans often have thousands, through which the base "
                             "edges cannot be traced")
    parser.add_argument("--drop-non-orientable", action="store_true",
                        help="drop the components that cannot be oriented (Moebius-like), "
                             "which no repair takes")
    parser.add_argument("--min-component-triangles", type=int, metavar="N",
                        default=prep.GetMinComponentTriangles(),
                        help=f"drop the components of fewer than N triangles, a scan's stray "
                             f"islands (default {prep.GetMinComponentTriangles()}: keep all)")
    parser.add_argument("--keep-largest-component", action="store_true",
                        help="keep only the component of the most triangles (a scanned object "
                             "without the debris around it)")


def _add_build_parser(sub, d):
    p = sub.add_parser("build", help="run the whole static pipeline and write the atlas")
    p.add_argument("mesh", help="mesh file (.ply, .ply.gz, .obj, .stl, .off, .vtp, .vtk), a "
                                "scene (.glb, .gltf, .fbx, .x, .md2) whose "
                                "surfaces are read in their rest pose, or a terrain raster "
                                "(.tif, .tiff, .asc, .hgt, .dem, .pgm, .png, .bmp)")
    _add_read_options(p)
    p.add_argument("-o", "--output", required=True, help="atlas file to write (.exr)")
    p.add_argument("--stages", metavar="DIR",
                   help="also write every stage as VTP (and pictures) into this folder")
    p.add_argument("--clusters", type=int, default=d.clusters.GetNumberOfClusters(),
                   help=f"number of spectral clusters (default "
                        f"{d.clusters.GetNumberOfClusters()})")
    p.add_argument("--crease-angle", type=float, default=d.features.GetCreaseAngle(),
                   help=f"dihedral angle in degrees of a crease, which straightened feature "
                        f"lines keep (default {d.features.GetCreaseAngle():g}; organic meshes "
                        f"simplify further with 60)")
    p.add_argument("--crease-lines", type=float, metavar="DEG",
                   default=d.features.GetCreaseLineAngle(),
                   help="chains of edges whose faces meet at DEG degrees or more also become "
                        "feature lines (default 0: only the cluster boundaries; CAD parts: 40)")
    p.add_argument("--base-faces", type=int, default=d.base.GetTargetFaces(),
                   help=f"target number of base-complex triangles (default "
                        f"{d.base.GetTargetFaces()})")
    p.add_argument("--max-error", type=float, default=d.base.GetMaxError(),
                   help="largest quadric error of a base-complex collapse, as a fraction of "
                        "the squared diagonal (default 1e-4, about 1%% of the diagonal RMS; "
                        "0: only --base-faces decides)")
    p.add_argument("--max-level", type=int, default=d.images.GetMaxLevel(),
                   help=f"largest chart level, 2^d + 1 samples per side (default "
                        f"{d.images.GetMaxLevel()})")
    p.add_argument("--error-target", type=float, default=d.images.GetErrorTarget(),
                   help=f"each chart's measured error is brought below this fraction of the "
                        f"diagonal, level by level (default {d.images.GetErrorTarget():g}; 0: "
                        f"no target, the budget alone)")
    p.add_argument("--budget", type=int, default=d.images.GetSampleBudget(),
                   help="total samples at the finest levels (default: as many as the error "
                        "target needs, up to 16 times the mesh's points; with --error-target 0 "
                        "the mesh's point count)")
    _add_repair_options(p, d)
    p.add_argument("--stretch-iterations", type=int, default=d.images.GetStretchIterations(),
                   help=f"stretch-reducing passes over each chart's mean-value map, "
                        f"{d.images.GetStretchIterationsMinValue()} .. "
                        f"{d.images.GetStretchIterationsMaxValue()} (default "
                        f"{d.images.GetStretchIterations()}; 0: the mean-value map alone)")
    p.add_argument("--no-seam-lines", action="store_true",
                   help="do not make the mesh's texture seams feature lines (each chart then "
                        "spans a seam and its texture smears across it)")
    p.add_argument("--skin-lines", action="store_true",
                   help="a skinned mesh: make the boundaries between the faces different joints "
                        "dominate feature lines, so that no chart straddles a bending joint "
                        "(more charts; helps a character of few bones most)")
    p.add_argument("--no-appearance", action="store_true",
                   help="leave the mesh's texture coordinates, vertex colours and base-colour "
                        "texture out of the atlas")
    p.add_argument("--no-fit", action="store_true",
                   help="interpolate the surface at the finest samples instead of fitting "
                        "them to it by least squares")
    p.add_argument("--threads", type=int, default=0,
                   help="threads of every stage, 1 .. 4096 (default 0: one per core); the "
                        "atlas is the same for every count")
    p.add_argument("--max-memory", type=memory_size, metavar="SIZE",
                   help="refuse, before the work starts, a build whose estimated peak memory "
                        "exceeds SIZE: bytes, or with a unit K, M, G, T (powers of 1024), "
                        "e.g. 8G, 512M; 0: no limit (default: the machine's available memory)")
    p.add_argument("--no-image", action="store_true", help="no pictures with --stages")
    p.add_argument("--json", action="store_true",
                   help="print the summary's figures as JSON instead of text")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")


# The --chain and --layout names, in the order of tcGLTFWriter's CHAIN_* and LAYOUT_*.
CHAINS = ("error", "uniform")
LAYOUTS = ("msft-lod", "named-nodes")


def _add_export_parser(sub, d):
    w = d.gltf
    p = sub.add_parser("export", help="write an atlas as a glTF 2.0 LOD chain (.glb, .gltf)")
    p.add_argument("atlas", help="atlas file (.exr)")
    p.add_argument("-o", "--output", required=True, help="glTF file to write (.glb or .gltf)")
    p.add_argument("--chain", choices=CHAINS, default=CHAINS[w.GetChain()],
                   help="error: each LOD lets the largest error grow by --error-ratio, every "
                        "chart at the coarsest level within it; uniform: one level for every "
                        f"chart per LOD (default {CHAINS[w.GetChain()]})")
    p.add_argument("--layout", choices=LAYOUTS, default=LAYOUTS[w.GetLayout()],
                   help="msft-lod: LOD 0 in the scene, the others linked by MSFT_lod; "
                        "named-nodes: every LOD in the scene as TriChart_LOD<k> (default "
                        f"{LAYOUTS[w.GetLayout()]})")
    p.add_argument("--error-ratio", type=float, default=w.GetErrorRatio(),
                   help=f"growth of the largest error per LOD (default {w.GetErrorRatio():g})")
    p.add_argument("--max-lods", type=int, default=w.GetMaxLods(),
                   help=f"most LODs written (default {w.GetMaxLods()})")
    p.add_argument("--error-pixels", type=float, default=w.GetErrorPixels(),
                   help=f"error an LOD may show for the screen-coverage hints (default "
                        f"{w.GetErrorPixels():g} px)")
    p.add_argument("--viewport-height", type=float, default=w.GetViewportHeight(),
                   help=f"viewport height of the hints (default {w.GetViewportHeight():g} px)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")


def _parser(d):
    """The command line: info, build, mesh, export, pose, eval and prepare, with the filters'
    defaults."""
    from .pipeline import MESH_EXTENSIONS

    formats = ", ".join(MESH_EXTENSIONS)
    parser = argparse.ArgumentParser(
        prog="trichart", description="TriChart: triangle-chart geometry images and LOD.")
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("info", help="versions, build type and the ParaView plugin path")
    _add_build_parser(sub, d)
    p = sub.add_parser("mesh", help="rebuild a mesh from an atlas at one level")
    p.add_argument("atlas", help="atlas file (.exr)")
    p.add_argument("--level", type=int, default=d.rebuild.GetLevel(),
                   help=f"level of every chart, capped by its finest (default "
                        f"{d.rebuild.GetLevel()}: finest)")
    p.add_argument("--time", type=float, help="a skinned atlas: pose it at this time (seconds)")
    p.add_argument("--animation", default="", help="with --time: the animation (name or index; "
                                                   "default the first)")
    p.add_argument("-o", "--output", required=True,
                   help="output mesh, in the format its extension names: " + formats)
    _add_export_parser(sub, d)
    p = sub.add_parser("pose", help="animations of a skinned scene or a sequence, and the mesh "
                                     "posed at a time")
    p.add_argument("source", help="a scene file (.glb, .gltf, .fbx, .x), an MD2 file, a folder "
                                  "of frames or a pattern such as 'frames/f_*.obj'")
    p.add_argument("--animation", default="", help="name or index of the animation (default: "
                                                   "the first)")
    p.add_argument("--time", type=float, help="seconds (a sequence: frame k at time k)")
    p.add_argument("-o", "--output", help="the posed mesh, in the format its extension names: " +
                   formats)
    p.add_argument("--skeleton", help="the posed skeleton (joints and bones as lines): .vtp or .vtk")
    p = sub.add_parser("eval", help="error of every level of an atlas against a mesh")
    p.add_argument("mesh", help="the original mesh")
    p.add_argument("atlas", help="atlas file (.exr)")
    p.add_argument("--samples", type=int, default=d.distance.GetSamplesPerMesh(),
                   help="samples per surface (default: chosen from the triangle counts)")
    p.add_argument("--json", action="store_true",
                   help="print every figure as JSON instead of the table")
    p.add_argument("--plot", metavar="PNG", help="also plot the errors against triangles")
    p.add_argument("--frames", type=int, default=0, metavar="N",
                   help="a skinned atlas: the finest level's error posed at N times evenly "
                        "over the animation, against the mesh posed alike")
    p.add_argument("--animation", default="", help="with --frames: the animation (name or "
                                                   "index; default the first)")
    _add_read_options(p)
    p = sub.add_parser("prepare", help="clean a mesh and write it")
    p.add_argument("mesh")
    p.add_argument("-o", "--output", required=True,
                   help="output mesh, in the format its extension names: " + formats)
    p.add_argument("--merge-tolerance", type=float, default=d.preparation.GetMergeTolerance(),
                   help="merge points closer than this fraction of the diagonal")
    _add_read_options(p)
    _add_repair_options(p, d)
    return parser


def _check_args(parser, args, d):
    """Refuses values out of the filters' ranges: the filters clamp them silently; a command
    line says what is wrong instead."""
    for name, value in vars(args).items():
        # argparse reads the '--' of `--clusters=--` as the end of the options and gives the
        # option an empty list: no option here takes a list, so it had no value.
        if isinstance(value, list):
            parser.error(f"--{name.replace('_', '-')} needs a value, not '--'")
    if args.command == "build":
        images, features, base = d.images, d.features, d.base
        low, high = images.GetStretchIterationsMinValue(), images.GetStretchIterationsMaxValue()
        if not low <= args.stretch_iterations <= high:
            parser.error(f"--stretch-iterations must be {low} .. {high}, not "
                         f"{args.stretch_iterations}")
        low, high = features.GetCreaseLineAngleMinValue(), features.GetCreaseLineAngleMaxValue()
        if not low <= args.crease_lines <= high:
            parser.error(f"--crease-lines must be {low:g} .. {high:g} degrees, not "
                         f"{args.crease_lines}")
        low, high = features.GetCreaseAngleMinValue(), features.GetCreaseAngleMaxValue()
        if not low <= args.crease_angle <= high:
            parser.error(f"--crease-angle must be {low:g} .. {high:g} degrees, not "
                         f"{args.crease_angle}")
        low, high = images.GetErrorTargetMinValue(), images.GetErrorTargetMaxValue()
        if not low <= args.error_target <= high:
            parser.error(f"--error-target must be {low:g} .. {high:g} (a fraction of the "
                         f"diagonal), not {args.error_target}")
        low, high = base.GetMaxErrorMinValue(), base.GetMaxErrorMaxValue()
        if not low <= args.max_error <= high:
            parser.error(f"--max-error must be {low:g} .. {high:g}, not {args.max_error}")
        if not 0 <= args.threads <= 4096:
            parser.error(f"--threads must be 1 .. 4096 (0: one per core), not {args.threads}")
    if args.command == "export":
        w = d.gltf
        for name, low, high in (("error_ratio", w.GetErrorRatioMinValue(), w.GetErrorRatioMaxValue()),
                                ("max_lods", w.GetMaxLodsMinValue(), w.GetMaxLodsMaxValue()),
                                ("error_pixels", w.GetErrorPixelsMinValue(),
                                 w.GetErrorPixelsMaxValue()),
                                ("viewport_height", w.GetViewportHeightMinValue(),
                                 w.GetViewportHeightMaxValue())):
            if not low <= getattr(args, name) <= high:
                parser.error(f"--{name.replace('_', '-')} must be {low:g} .. {high:g}, not "
                             f"{getattr(args, name)}")
    if args.command in ("build", "prepare", "eval") and not args.vertical_scale > 0:
        parser.error(f"--vertical-scale must be above 0, not {args.vertical_scale}")
    if args.command in ("build", "prepare") and (args.max_hole_edges < 0 or
                                                 0 < args.max_hole_edges < 3):
        parser.error(f"--max-hole-edges must be 3 or more (0: any size), not "
                     f"{args.max_hole_edges}")
    if args.command in ("build", "prepare") and args.min_component_triangles < 0:
        parser.error(f"--min-component-triangles must be 0 (keep all) or more, not "
                     f"{args.min_component_triangles}")


def _route_vtk_messages():
    """VTK's warnings and stray errors as one `trichart: warning: ...` line each on stderr:
    without the logger's time stamps, colour codes, file and line or object addresses, which
    say nothing to a user (the command reports what matters itself)."""
    from vtkmodules.util.misc import calldata_type
    from vtkmodules.util.vtkConstants import VTK_STRING
    from vtkmodules.vtkCommonCore import vtkCommand, vtkLogger, vtkOutputWindow

    @calldata_type(VTK_STRING)
    def show(_window, event, text):
        message = text.split("\n", 1)[-1].strip()  # after "Warning: In file, line N"
        message = re.sub(r"^(\w+) \(0x[0-9a-fA-F]+\): ", r"\1: ", message)
        kind = "warning" if event == "WarningEvent" else "error"
        print(f"trichart: {kind}: {message}", file=sys.stderr)

    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)
    window = vtkOutputWindow.GetInstance()
    window.SetDisplayModeToNever()
    for event in (vtkCommand.WarningEvent, vtkCommand.ErrorEvent):
        window.AddObserver(event, show)
    _route_vtk_messages.keep = (window, show)  # the observer lives as long as the process


def main(argv=None):
    try:
        return _main(argv)
    except KeyboardInterrupt:  # SIGINT before or between the stages (run() defers it in one)
        print("trichart: interrupted; nothing half-written was left", file=sys.stderr)
        return 130
    except BrokenPipeError:
        # The reader of the output went away (`| head`): stop quietly, as a shell tool does, and
        # keep Python from reporting the failed flush of stdout at exit.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 128 + 13  # SIGPIPE


def _main(argv):
    defaults = _Defaults()
    parser = _parser(defaults)
    args = parser.parse_args(argv)
    _check_args(parser, args, defaults)

    if _needs_display(args) and not os.environ.get("DISPLAY"):
        _reexec_under_xvfb()

    from .pipeline import TriChartError

    _route_vtk_messages()

    try:
        commands = {"info": cmd_info, "build": cmd_build, "mesh": cmd_mesh, "eval": cmd_eval,
                    "prepare": cmd_prepare, "export": cmd_export, "pose": cmd_pose}
        return commands[args.command](args)
    except TriChartError as error:
        print(f"trichart: error: {error}", file=sys.stderr)
        return 2
