"""The `trichart` command: run TriChart stages on mesh files from the shell."""
import argparse
import os
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


def _needs_display(args):
    return args.command == "build" and not args.no_image


def _reexec_under_xvfb():
    """Rendering needs an X display (Debian's VTK has no offscreen-only back end): when there
    is none, run this same command again under xvfb-run."""
    xvfb = shutil.which("xvfb-run")
    if not xvfb or os.environ.get("TRICHART_UNDER_XVFB"):
        return False
    env = dict(os.environ, TRICHART_UNDER_XVFB="1")
    os.execvpe(xvfb, [xvfb, "-a", "-s", "-screen 0 1280x1024x24", sys.executable, "-m",
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


def cmd_build(args):
    from .pipeline import build

    bar = None if args.quiet else ProgressBar()
    start = time.perf_counter()
    try:
        result = build(args.mesh, args.output, progress=bar, image=not args.no_image,
                       cluster_options={"number_of_clusters": args.clusters},
                       base_options={"target_faces": args.base_faces})
    finally:
        if bar:
            bar.close()
    seconds = time.perf_counter() - start
    surface, crest = result["surface"], result["crest_lines"]
    print(f"{args.mesh}: {surface.GetNumberOfPoints()} points, "
          f"{surface.GetNumberOfCells()} triangles, {crest.GetNumberOfCells()} crest lines, "
          f"{result['feature_lines'].GetNumberOfCells()} feature lines, "
          f"{result['corners'].GetNumberOfPoints()} corners, "
          f"{result['base_complex'].GetNumberOfPolys()} base triangles ({seconds:.2f} s)")
    for line in result["report"].splitlines():
        print(f"  prepared: {line}")
    for name, path in result["files"].items():
        print(f"  wrote {name}: {path}")
    return 0


def cmd_prepare(args):
    from .pipeline import prepare, read_mesh, write_vtp

    clean, report = prepare(read_mesh(args.mesh), merge_tolerance=args.merge_tolerance,
                            split_non_manifold=args.split_non_manifold)
    print(report.strip() or "nothing to change")
    print(f"wrote {write_vtp(clean, args.output)}")
    return 0


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="trichart", description="TriChart: triangle-chart geometry images and LOD.")
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("info", help="versions, build type and the ParaView plugin path")
    p = sub.add_parser("build", help="run the pipeline on a mesh and write every stage")
    p.add_argument("mesh", help="mesh file (.ply, .ply.gz, .obj, .stl, .off, .vtp, .vtk)")
    p.add_argument("-o", "--output", required=True, help="output folder")
    p.add_argument("--clusters", type=int, default=16,
                   help="number of spectral clusters (default 16)")
    p.add_argument("--base-faces", type=int, default=100,
                   help="target number of base-complex triangles (default 100)")
    p.add_argument("--no-image", action="store_true", help="do not render a PNG")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    p = sub.add_parser("prepare", help="clean a mesh and write it as VTP")
    p.add_argument("mesh")
    p.add_argument("-o", "--output", required=True, help="output .vtp file")
    p.add_argument("--merge-tolerance", type=float, default=0.0,
                   help="merge points closer than this fraction of the diagonal")
    p.add_argument("--split-non-manifold", action="store_true")
    args = parser.parse_args(argv)

    if _needs_display(args) and not os.environ.get("DISPLAY"):
        _reexec_under_xvfb()

    from vtkmodules.vtkCommonCore import vtkLogger

    from .pipeline import TriChartError

    # The command reports what matters itself; VTK's INFO lines would bury it.
    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_WARNING)

    try:
        return {"info": cmd_info, "build": cmd_build, "prepare": cmd_prepare}[args.command](args)
    except TriChartError as error:
        print(f"trichart: error: {error}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("trichart: aborted", file=sys.stderr)
        return 130
