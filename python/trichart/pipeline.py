"""Chain the TriChart filters from Python, with errors as exceptions and progress callbacks."""
import os
import tempfile

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

from . import (TriChartBaseComplex, TriChartCurvature, TriChartFeatures,
               TriChartGeometryImages, TriChartIO, TriChartPreparation)


class TriChartError(RuntimeError):
    """A TriChart stage refused its input; the message says what to fix."""


class UntraceableError(TriChartError):
    """tcPathTracing could not trace the paths (the parameterization is not one-to-one
    somewhere, which slivers cause); `reason` says what could not be traced."""

    def __init__(self, message, reason):
        super().__init__(message)
        self.reason = reason


def run(algorithm, label="", progress=None):
    """Update `algorithm`; raise TriChartError with its error message if it fails.

    progress(label, fraction) is called as the algorithm reports progress; returning False
    from it (or pressing Ctrl-C) aborts the stage.
    """
    errors = []

    @calldata_type(VTK_STRING)
    def on_error(_obj, _event, text):
        errors.append(text.strip())

    def on_progress(obj, _event):
        try:
            if progress is not None and progress(label, obj.GetProgress()) is False:
                obj.AbortExecuteOn()
        except KeyboardInterrupt:
            obj.AbortExecuteOn()
            errors.append("interrupted")

    def on_executive_error(_obj, _event):
        pass  # "Algorithm ... returned failure for request" and a dump of the request: the
        # algorithm's own message (above) says what went wrong

    error_tag = algorithm.AddObserver(vtkCommand.ErrorEvent, on_error)
    progress_tag = algorithm.AddObserver(vtkCommand.ProgressEvent, on_progress)
    executive = algorithm.GetExecutive()
    executive_tag = executive.AddObserver(vtkCommand.ErrorEvent, on_executive_error)
    try:
        algorithm.Update()
    finally:
        algorithm.RemoveObserver(error_tag)
        algorithm.RemoveObserver(progress_tag)
        executive.RemoveObserver(executive_tag)
    if algorithm.GetAbortExecute():
        algorithm.AbortExecuteOff()
        algorithm.Modified()
        raise KeyboardInterrupt(f"{label or algorithm.GetClassName()} aborted")
    if errors:
        # Keep the part after VTK's "ERROR: In file, line N / class (address):" preamble.
        message = errors[0].split("\n", 1)[-1].strip()
        raise TriChartError(f"{label or algorithm.GetClassName()}: {message}")
    return algorithm


def _output(algorithm, port=0):
    from vtkmodules.vtkCommonDataModel import vtkPolyData

    copy = vtkPolyData()
    copy.ShallowCopy(algorithm.GetOutputDataObject(port))
    return copy


def read_mesh(path, progress=None):
    """Read a mesh file (.ply, .ply.gz, .obj, .stl, .off, .vtp, .vtk), or the surfaces of a
    scene file (.glb, .gltf, .fbx, .x, .md2) in their rest pose, into a vtkPolyData."""
    reader = TriChartIO.tcMeshReader()
    reader.SetFileName(str(path))
    run(reader, "read", progress)
    return _output(reader)


def prepare(mesh, merge_tolerance=0.0, split_non_manifold=False, orient=True, fill_holes=False,
            max_hole_edges=1000, remove_slivers=False, sliver_angle=170.0,
            sliver_edge_ratio=10.0, progress=None):
    """tcMeshPreparation on `mesh`; returns (clean mesh, report text)."""
    f = _prepared(mesh, progress, merge_tolerance=merge_tolerance,
                  split_non_manifold=split_non_manifold, orient=orient, fill_holes=fill_holes,
                  max_hole_edges=max_hole_edges, remove_slivers=remove_slivers,
                  sliver_angle=sliver_angle, sliver_edge_ratio=sliver_edge_ratio)
    return _output(f), f.GetReport()


def _prepared(mesh, progress=None, **options):
    """tcMeshPreparation on `mesh` with `options` (prepare's, the filter's defaults for those not
    given), run; returns the filter (its output, report and counts)."""
    f = _configure(TriChartPreparation.tcMeshPreparation(), options)
    f.SetInputData(mesh)
    run(f, "prepare", progress)
    return f


def _closed_manifold_check(f):
    """Raise TriChartError, before the stages that need one, when tcMeshPreparation `f` did not
    give a closed, oriented manifold, with what to turn on (the preparation's own text)."""
    if f.GetClosedManifold():
        return
    raise TriChartError("prepare: the prepared mesh is not a closed, oriented manifold, which "
                        "the base complex needs: " + f.GetClosedManifoldRepairs())


def _configure(algorithm, options):
    """Set properties from snake-case keyword options (min_neighbors -> SetMinNeighbors)."""
    for name, value in options.items():
        setter = "Set" + "".join(part[:1].upper() + part[1:] for part in name.split("_"))
        if not hasattr(algorithm, setter):
            raise TypeError(f"{algorithm.GetClassName()} has no option '{name}'")
        getattr(algorithm, setter)(value)
    return algorithm


def curvature(mesh, progress=None, **options):
    """tcCurvature on a triangle mesh; returns (mesh with curvature arrays, crest lines).

    Options are the filter's properties in snake case: min_neighbors, max_rings, degree,
    robust, robust_iterations, compute_crest_lines, crest_strength_threshold.
    """
    f = _configure(TriChartCurvature.tcCurvature(), options)
    f.SetInputData(mesh)
    run(f, "curvature", progress)
    return _output(f, 0), _output(f, 1)


def cluster(surface, progress=None, **options):
    """tcSpectralClustering on tcCurvature's output; returns (mesh with ClusterId, boundaries).

    Options: number_of_clusters, number_of_eigenvectors, crest_beta, extra_edge_factor,
    nystrom_threshold, nystrom_samples, k_means_restarts, seed.
    """
    f = _configure(TriChartFeatures.tcSpectralClustering(), options)
    f.SetInputData(surface)
    run(f, "clusters", progress)
    return _output(f, 0), _output(f, 1)


def refine_features(clusters, progress=None, **options):
    """tcFeatureRefinement on tcSpectralClustering's output; returns (mesh with FeatureVertex
    and CornerVertex, feature lines, corners).

    Options: band_fraction, crest_beta, curvature_top_fraction, curvature_threshold_scale,
    corner_rings, corner_fraction, band_rings, cut_passes, dihedral_weight, junction_corners,
    straighten_lines (straighten one-face zig-zags of the boundaries, default True),
    crease_angle (degrees; straightening never trades a crease edge for a smoother one).
    """
    f = _configure(TriChartFeatures.tcFeatureRefinement(), options)
    f.SetInputData(clusters)
    run(f, "features", progress)
    return _output(f, 0), _output(f, 1), _output(f, 2)


def base_complex(features, progress=None, **options):
    """tcBaseComplex on a closed manifold mesh (normally refine_features' output); returns
    (base complex, input mesh with BaseFaceId and BaseBarycentric).

    Options: target_faces, max_error.
    """
    f = _configure(TriChartBaseComplex.tcBaseComplex(), options)
    f.SetInputData(features)
    run(f, "base", progress)
    return _output(f, 0), _output(f, 1)


def trace_paths(parameterized, progress=None):
    """tcPathTracing on base_complex's second output; returns (patches with PatchId, paths)."""
    f = TriChartGeometryImages.tcPathTracing()
    f.SetInputData(parameterized)
    try:
        run(f, "paths", progress)
    except TriChartError as error:
        if f.GetUntraceable():
            raise UntraceableError(str(error), f.GetUntraceableReason()) from None
        raise
    return _output(f, 0), _output(f, 1)


def _multiblock(algorithm, port=0):
    from vtkmodules.vtkCommonDataModel import vtkMultiBlockDataSet

    copy = vtkMultiBlockDataSet()
    copy.ShallowCopy(algorithm.GetOutputDataObject(port))
    return copy


def geometry_images(patches, resampled_arrays=(), progress=None, **options):
    """tcGeometryImages on trace_paths' first output; returns the atlas (a multiblock of the
    chart table and one image per mip step).

    Options: sample_budget, min_level, max_level, curvature_weight, level_rule (0: by
    curvature-weighted area, 1: by measured error, the default), stretch_iterations
    (stretch-reducing passes over each mean-value map, default 10; 0: Floater's map alone).
    """
    f = _configure(TriChartGeometryImages.tcGeometryImages(), options)
    for name in resampled_arrays:
        f.AddResampledArray(name)
    f.SetInputData(patches)
    run(f, "images", progress)
    return _multiblock(f)


def rebuild(atlas, level=-1, chart_levels=None, progress=None):
    """tcGeometryImageMesh: the mesh of `atlas` with every chart at `level` (-1: its finest),
    or at chart_levels[c] for chart c, stitched without cracks."""
    f = TriChartGeometryImages.tcGeometryImageMesh()
    f.SetInputData(atlas)
    f.SetLevel(level)
    if chart_levels is not None:
        from vtkmodules.vtkCommonCore import vtkIntArray

        levels = vtkIntArray()
        for value in chart_levels:
            levels.InsertNextValue(int(value))
        f.SetChartLevels(levels)
    run(f, "rebuild", progress)
    return _output(f)


def surface_distance(mesh, reference, progress=None, **options):
    """tcSurfaceDistance; returns (mesh with point array Distance, figures) where figures has
    hausdorff, mean, rms (absolute) and diagonal (of the reference's bounding box).

    Options: samples_per_mesh, seed.
    """
    f = _configure(TriChartGeometryImages.tcSurfaceDistance(), options)
    f.SetInputData(0, mesh)
    f.SetInputData(1, reference)
    run(f, "distance", progress)
    figures = {"hausdorff": f.GetHausdorff(), "mean": f.GetMeanDistance(),
               "rms": f.GetRmsDistance(), "diagonal": f.GetDiagonal()}
    return _output(f), figures


def read_atlas(path, progress=None):
    """Read an atlas file (.exr) into the atlas multiblock."""
    reader = TriChartIO.tcAtlasReader()
    reader.SetFileName(str(path))
    run(reader, "read atlas", progress)
    return _multiblock(reader)


def write_atlas(atlas, path, progress=None):
    """Write the atlas multiblock as one OpenEXR file (temporary file renamed at the end)."""
    writer = TriChartIO.tcAtlasWriter()
    writer.SetFileName(str(path))
    writer.SetInputData(atlas)
    run(writer, "write atlas", progress)
    if writer.GetErrorCode() != 0:
        raise TriChartError(f"cannot write the atlas '{path}'")
    return os.path.abspath(str(path))


def atlas_charts(atlas):
    """The chart table of an atlas multiblock (vtkTable)."""
    return atlas.GetBlock(0)


def write_vtp(mesh, path):
    """Write `mesh` as VTP; the file appears only when complete (temporary file, then rename)."""
    path = os.path.abspath(str(path))
    folder = os.path.dirname(path)
    fd, tmp = tempfile.mkstemp(prefix=".tmp-", suffix=".vtp", dir=folder)
    os.close(fd)
    try:
        writer = vtkXMLPolyDataWriter()
        writer.SetFileName(tmp)
        writer.SetInputData(mesh)
        writer.SetDataModeToBinary()
        if writer.Write() != 1:
            raise TriChartError(f"cannot write '{path}' (disk full or not writable?)")
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return path


def build(path, atlas_path, stages=None, progress=None, image=True, curvature_options=None,
          cluster_options=None, feature_options=None, base_options=None,
          geometry_options=None, prepare_options=None, retry_slivers=True):
    """The static pipeline: read, prepare, curvature, spectral clusters, feature refinement,
    base complex with MAPS, path tracing, geometry images; writes the atlas to `atlas_path`.

    With `stages` (a folder) every stage is also written there as VTP (prepared, curvature,
    crest_lines, clusters, cluster_boundaries, features, feature_lines, corners, base_complex,
    parameterized, patches, paths, and the rebuilt mesh at the finest level as rebuilt), and,
    with image=True, pictures of curvature, features and the base complex. Returns a dict with
    every output, the written paths, the preparation report and the seconds per stage.

    The prepared mesh must be a closed, oriented manifold: otherwise TriChartError says, right
    after the preparation, which of its options (prepare_options) to turn on.

    With retry_slivers (the default), when the paths cannot be traced and the preparation did
    not remove slivers, it is run again with remove_slivers=True and the stages after it too:
    slivers are what makes the parameterization too thin to trace on scans and CAD meshes.
    The result's "retried" then says so (None otherwise).
    """
    import time

    seconds = {}

    def timed(name, function, *args, **kwargs):
        start = time.perf_counter()
        value = function(*args, **kwargs)
        seconds[name] = time.perf_counter() - start
        return value

    mesh = timed("read", read_mesh, path, progress)

    def front(options):
        prepared = timed("prepare", _prepared, mesh, progress=progress, **options)
        # Fail here, not after curvature, clusters and features have run for minutes.
        _closed_manifold_check(prepared)
        clean, report = _output(prepared), prepared.GetReport()
        surface, crest = timed("curvature", curvature, clean, progress=progress,
                               **(curvature_options or {}))
        clustered, boundaries = timed("clusters", cluster, surface, progress=progress,
                                      **(cluster_options or {}))
        features, lines, corners = timed("features", refine_features, clustered,
                                         progress=progress, **(feature_options or {}))
        base, parameterized = timed("base", base_complex, features, progress=progress,
                                    **(base_options or {}))
        patches, paths = timed("paths", trace_paths, parameterized, progress=progress)
        return (clean, report, surface, crest, clustered, boundaries, features, lines, corners,
                base, parameterized, patches, paths)

    options = dict(prepare_options or {})
    retried = None
    try:
        stages_out = front(options)
    except UntraceableError as error:
        if not retry_slivers or options.get("remove_slivers"):
            raise
        retried = (f"the paths could not be traced ({error.reason}); built again "
                   "with the slivers removed (--remove-slivers)")
        options["remove_slivers"] = True
        stages_out = front(options)
    (clean, report, surface, crest, clustered, boundaries, features, lines, corners, base,
     parameterized, patches, paths) = stages_out
    atlas = timed("images", geometry_images, patches, progress=progress,
                  **(geometry_options or {}))
    os.makedirs(os.path.dirname(os.path.abspath(str(atlas_path))), exist_ok=True)
    files = {"atlas": timed("write", write_atlas, atlas, atlas_path, progress)}
    outputs = {"prepared": clean, "curvature": surface, "crest_lines": crest,
               "clusters": clustered, "cluster_boundaries": boundaries, "features": features,
               "feature_lines": lines, "corners": corners, "base_complex": base,
               "parameterized": parameterized, "patches": patches, "paths": paths}
    if stages:
        os.makedirs(stages, exist_ok=True)
        outputs["rebuilt"] = rebuild(atlas, progress=progress)
        files.update({name: write_vtp(data, os.path.join(stages, f"{name}.vtp"))
                      for name, data in outputs.items()})
        if image:
            from .render import render_base_complex, render_curvature, render_features

            files["curvature_image"] = render_curvature(
                surface, crest, os.path.join(stages, "curvature.png"))
            files["features_image"] = render_features(
                features, lines, corners, os.path.join(stages, "features.png"))
            files["base_complex_image"] = render_base_complex(
                base, parameterized, os.path.join(stages, "base_complex.png"))
    return dict(outputs, atlas=atlas, files=files, report=report, mesh=clean, surface=surface,
                seconds=seconds, retried=retried)
