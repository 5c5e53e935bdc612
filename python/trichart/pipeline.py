"""Chain the TriChart filters from Python, with errors as exceptions and progress callbacks."""
import os
import signal
import threading
import time

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline

from . import (TriChartBaseComplex, TriChartCurvature, TriChartFeatures, TriChartSkinning,
               TriChartGeometryImages, TriChartIO, TriChartMultilevel, TriChartPreparation)


class TriChartError(RuntimeError):
    """A TriChart stage refused its input; the message says what to fix."""


class ResourceError(TriChartError):
    """A request needs more memory than its limit; `estimate` and `limit` are in bytes."""

    def __init__(self, message, estimate, limit):
        super().__init__(message)
        self.estimate = estimate
        self.limit = limit


class UntraceableError(TriChartError):
    """tcPathTracing could not trace the paths (the parameterization is not one-to-one
    somewhere, which slivers cause); `reason` says what could not be traced."""

    def __init__(self, message, reason):
        super().__init__(message)
        self.reason = reason


class _DeferredInterrupt:
    """While a filter runs, SIGINT only records the request, which the next progress event turns
    into an abort: a KeyboardInterrupt raised inside a VTK observer makes VTK's wrapping exit the
    process on the spot (exit code 1, no unwinding, a writer's temporary file left behind).
    Installed only over Python's own handler, in the main thread; `requested` says whether a
    SIGINT came."""

    def __init__(self):
        self.requested = False
        self.previous = None

    def __enter__(self):
        if (threading.current_thread() is threading.main_thread()
                and signal.getsignal(signal.SIGINT) is signal.default_int_handler):
            self.previous = signal.signal(signal.SIGINT, self._record)
        return self

    def _record(self, _signum, _frame):
        self.requested = True

    def __exit__(self, *_exc):
        if self.previous is not None:
            signal.signal(signal.SIGINT, self.previous)
        return False


def run(algorithm, label="", progress=None):
    """Update `algorithm`; raise TriChartError with its error message if it fails.

    progress(label, fraction) is called as the algorithm reports progress; returning False
    from it (or pressing Ctrl-C) aborts the stage, and KeyboardInterrupt is raised when it has
    stopped (its outputs and files cleaned up by the filter).
    """
    errors = []
    interrupt = _DeferredInterrupt()

    @calldata_type(VTK_STRING)
    def on_error(_obj, _event, text):
        errors.append(text.strip())

    def on_progress(obj, _event):
        try:
            if interrupt.requested or (progress is not None and
                                       progress(label, obj.GetProgress()) is False):
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
        with interrupt:
            algorithm.Update()
    finally:
        algorithm.RemoveObserver(error_tag)
        algorithm.RemoveObserver(progress_tag)
        executive.RemoveObserver(executive_tag)
    if algorithm.GetAbortExecute() or interrupt.requested:
        algorithm.AbortExecuteOff()
        algorithm.Modified()
        raise KeyboardInterrupt(f"{label or algorithm.GetClassName()} aborted")
    if errors:
        # Keep the part after VTK's "ERROR: In file, line N / class (address):" preamble.
        message = errors[0].split("\n", 1)[-1].strip()
        raise TriChartError(f"{label or algorithm.GetClassName()}: {message}")
    return algorithm


def set_max_threads(n):
    """Caps the threads of every TriChart stage of this process at n (0: one per core)."""
    if not TriChartIO.tcResources.SetMaxThreads(int(n)):
        raise TriChartError(f"threads must be 0 .. 4096 (0: one per core), not {n}")


def format_bytes(n):
    """A byte count for a message: '512.0 MB', '80.1 GB' (powers of 1024, as --max-memory)."""
    for unit, scale in (("TB", 2 ** 40), ("GB", 2 ** 30), ("MB", 2 ** 20), ("KB", 2 ** 10)):
        if abs(n) >= scale:
            return f"{n / scale:.1f} {unit}"
    return f"{n} bytes"


def _stage_defaults():
    """The options of the estimate that the filters default (one home for each)."""
    images = TriChartGeometryImages.tcGeometryImages()
    return {"max_level": images.GetMaxLevel(), "sample_budget": images.GetSampleBudget(),
            "error_target": images.GetErrorTarget(),
            "target_faces": TriChartBaseComplex.tcBaseComplex().GetTargetFaces(),
            "nystrom_threshold": TriChartFeatures.tcSpectralClustering().GetNystromThreshold()}


def estimate_memory(points, triangles, geometry_options=None, base_options=None,
                    cluster_options=None):
    """Estimated peak memory in bytes of build() on a mesh of these counts with these options
    (the filters' defaults for those not given), above what the process holds before it."""
    options = _stage_defaults()
    for given in (geometry_options, base_options, cluster_options):
        options.update({k: v for k, v in (given or {}).items() if k in options})
    estimate = TriChartIO.tcResources.EstimateBuildMemory(
        int(points), int(triangles), int(options["sample_budget"]), int(options["max_level"]),
        int(options["target_faces"]), int(options["nystrom_threshold"]),
        float(options["error_target"]))
    if estimate < 0:
        raise TriChartError(f"memory: no estimate for a budget of {options['sample_budget']} "
                            f"samples up to level {options['max_level']}: the budget must not "
                            f"be negative and the largest level must be 0 .. 12")
    return estimate


def _check_memory(points, triangles, limit, what, options):
    """Raise ResourceError when the build of a mesh of these counts needs more than `limit`
    bytes (None: the available memory; 0: no limit); returns the estimate."""
    estimate = estimate_memory(points, triangles, *options)
    source = "--max-memory / max_memory"
    if limit is None:
        limit, source = TriChartIO.tcResources.GetAvailableMemory(), "the available memory"
    if limit and estimate > limit:
        images = dict(_stage_defaults(), **(options[0] or {}))
        budget = images["sample_budget"] or points
        raise ResourceError(
            f"memory: {what} {points} points and {triangles} triangles; with a budget of "
            f"{budget} samples up to level {images['max_level']} its build needs about "
            f"{format_bytes(estimate)}, more than the limit of {format_bytes(limit)} "
            f"({source}): lower the budget or the largest level (--budget, --max-level), "
            f"simplify the mesh, or raise the limit (--max-memory)", estimate, limit)
    return estimate


def resident_memory(field="VmRSS"):
    """Bytes this process holds now (VmRSS) or held at most (VmHWM), 0 where /proc does not
    say."""
    try:
        with open("/proc/self/status") as status:
            for line in status:
                if line.startswith(field + ":"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 0


def reset_peak_memory():
    """Start VmHWM again from what the process holds now (Linux's /proc/self/clear_refs), so
    that a later peak is that of the work since, not of what came before (imports, argument
    defaults) and was freed; nothing where /proc does not allow it."""
    try:
        with open("/proc/self/clear_refs", "w") as refs:
            refs.write("5")
    except OSError:
        pass


def _output(algorithm, port=0):
    from vtkmodules.vtkCommonDataModel import vtkPolyData

    copy = vtkPolyData()
    copy.ShallowCopy(algorithm.GetOutputDataObject(port))
    return copy


def _mesh_reader(path, animation, bind_pose, proxy_bones=True, vertical_scale=1.0):
    reader = TriChartIO.tcMeshReader()
    reader.SetFileName(str(path))
    reader.SetVerticalScale(float(vertical_scale))
    reader.SetAnimation("" if animation is None else str(animation))
    reader.SetBindPose(bool(bind_pose))
    reader.SetProxyBones(bool(proxy_bones))
    return reader


def _run_at(reader, time, label, progress):
    info = reader.GetOutputInformation(0)
    key = vtkStreamingDemandDrivenPipeline.UPDATE_TIME_STEP()
    if time is not None:
        reader.UpdateInformation()
        info.Set(key, float(time))
    elif info.Has(key):  # back to the rest pose after a posed read
        info.Remove(key)
        reader.Modified()
    return run(reader, label, progress)


def read_mesh(path, progress=None, time=None, animation=None, bind_pose=False,
              proxy_bones=True, vertical_scale=1.0):
    """Read a mesh file (.ply, .ply.gz, .obj, .stl, .off, .vtp, .vtk), the surfaces of a
    scene file (.glb, .gltf, .fbx, .x, .md2), a deforming sequence (a folder of frames, a
    pattern such as 'frames/f_*.obj', or an MD2 file's keyframes), or a terrain raster
    through GDAL (.tif, .tiff, .asc, .hgt, .dem, .pgm, .png, .bmp: a grid in metres with the
    point array Elevation, heights times vertical_scale) into a vtkPolyData.

    Without `time`, the rest pose (a sequence's first frame); with it (seconds), the scene
    posed by `animation` (its name or index; the first by default) or the sequence's frame
    at that time. bind_pose=True reads the rest pose and announces no time steps.
    proxy_bones=False reads a sequence without fitting proxy bones (no skin)."""
    reader = _mesh_reader(path, animation, bind_pose, proxy_bones, vertical_scale)
    _run_at(reader, time, "read", progress)
    return _output(reader)


def read_frames(path, times, animation=None, progress=None):
    """read_mesh at each of `times` (None: the rest pose), one vtkPolyData each, through one
    reader: the file is read, and a sequence's proxy bones fitted, once for all of them."""
    reader = _mesh_reader(path, animation, False)
    for when in times:
        _run_at(reader, when, "read", progress)
        yield _output(reader)


def read_skeleton(path, time=None, animation=None):
    """The skeleton of a skinned or animated scene file as polydata (a point per joint, a
    line to its parent; point arrays JointNames, JointParent, InverseBindMatrices,
    JointTransforms), posed at `time` like read_mesh; empty for a file without one."""
    reader = _mesh_reader(path, animation, False)
    _run_at(reader, time, "read", None)
    return _output(reader, 1)


def time_steps(path, animation=None):
    """The times (seconds) a scene's animation or a sequence's frames are announced at, or a
    skinned atlas's (.exr: its rig's animation, as the mesh it was built from announces them);
    () for a static mesh or atlas."""
    if TriChartIO.tcAtlasReader.CanReadFile(str(path)):
        reader = TriChartIO.tcAtlasReader()
        reader.SetFileName(str(path))
        reader.SetAnimation("" if animation is None else str(animation))
        run(reader, "read atlas")
    else:
        reader = _mesh_reader(path, animation, False)
        run(reader, "read")
    info = reader.GetOutputInformation(0)
    key = vtkStreamingDemandDrivenPipeline.TIME_STEPS()
    return tuple(info.Get(key)) if info.Has(key) else ()


def pose(mesh, time, animation=None, progress=None):
    """tcLinearBlendSkinning: `mesh` (with SkinIndices, SkinWeights and the Rig field: a
    skinned scene read with bind_pose=True, or a rebuilt skinned atlas) posed at `time`
    seconds of `animation` (name or index; the first by default)."""
    f = TriChartSkinning.tcLinearBlendSkinning()
    f.SetInputData(mesh)
    f.SetTime(float(time))
    f.SetAnimation("" if animation is None else str(animation))
    run(f, "pose", progress)
    return _output(f)


def deformation_clustering(path, progress=None, animation=None, **options):
    """tcDeformationClustering on the sequence (a folder of frames, a pattern, an MD2 file) or
    skinned scene at `path`: every frame is read, the faces are clustered by their deformation
    and a proxy bone is fitted to each cluster (a mesh skinned to a skeleton of its own is
    grouped by its dominant joints instead). Returns (the first frame with ClusterId,
    FeatureVertex and the proxy skin, the cluster boundaries as lines, a dict of the fit's
    per-frame "rms", "max" and "rigid_rms" as fractions of the diagonal; empty lists for a
    skinned mesh).

    Options are the filter's properties in snake case: number_of_clusters,
    gradient_sigma_scale, seed, max_influences, iterations."""
    # The reader's own proxy bones would be fitted and then replaced: leave them out.
    reader = _mesh_reader(path, animation, False, proxy_bones=False)
    f = _configure(TriChartSkinning.tcDeformationClustering(), options)
    f.SetInputConnection(reader.GetOutputPort())
    run(f, "deformation clusters", progress)
    clusters = _output(f)
    fields = clusters.GetFieldData()

    def values(name):
        array = fields.GetArray(name)
        return [array.GetValue(k) for k in range(array.GetNumberOfTuples())] if array else []

    fit = {"rms": values(TriChartIO.tcArrayNames.FitRms()), "max": values(TriChartIO.tcArrayNames.FitMax()),
           "rigid_rms": values(TriChartIO.tcArrayNames.RigidFitRms())}
    return clusters, _output(f, 1), fit


def animation_names(path):
    """The names of a scene file's animations, in the file's order."""
    reader = _mesh_reader(path, None, True)
    run(reader, "read")
    return [reader.GetAnimationName(a) for a in range(reader.GetNumberOfAnimations())]


def prepare(mesh, progress=None, **options):
    """tcMeshPreparation on `mesh`; returns (clean mesh, report text).

    Options are the filter's properties in snake case, its defaults for those not given:
    merge_tolerance, split_non_manifold, orient, fill_holes, max_hole_edges, remove_slivers,
    sliver_angle, sliver_edge_ratio, drop_non_orientable, min_component_triangles,
    keep_largest_component.
    """
    f = _prepared(mesh, progress, **options)
    return _output(f), f.GetReport()


def _prepared(mesh, progress=None, **options):
    """tcMeshPreparation on `mesh` with `options` (prepare's, the filter's defaults for those not
    given), run; returns the filter (its output, report and counts)."""
    return _run_on(TriChartPreparation.tcMeshPreparation(), mesh, "prepare", progress, options)


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


def _run_on(algorithm, data, label, progress, options):
    """`algorithm` with `options` (snake case) on input `data`, run; returns the algorithm."""
    _configure(algorithm, options)
    algorithm.SetInputData(data)
    run(algorithm, label, progress)
    return algorithm


def curvature(mesh, progress=None, **options):
    """tcCurvature on a triangle mesh; returns (mesh with curvature arrays, crest lines).

    Options are the filter's properties in snake case: min_neighbors, max_rings, degree,
    robust, robust_iterations, compute_crest_lines, crest_strength_threshold.
    """
    f = _run_on(TriChartCurvature.tcCurvature(), mesh, "curvature", progress, options)
    return _output(f, 0), _output(f, 1)


def cluster(surface, progress=None, **options):
    """tcSpectralClustering on tcCurvature's output; returns (mesh with ClusterId, boundaries).

    Options: number_of_clusters, number_of_eigenvectors, crest_beta, extra_edge_factor,
    nystrom_threshold, nystrom_samples, k_means_restarts, seed.
    """
    f = _run_on(TriChartFeatures.tcSpectralClustering(), surface, "clusters", progress, options)
    return _output(f, 0), _output(f, 1)


def refine_features(clusters, progress=None, **options):
    """tcFeatureRefinement on tcSpectralClustering's output; returns (mesh with FeatureVertex
    and CornerVertex, feature lines, corners).

    Options: band_fraction, crest_beta, curvature_top_fraction, curvature_threshold_scale,
    corner_rings, corner_fraction, band_rings, cut_passes, dihedral_weight, junction_corners,
    straighten_lines (straighten one-face zig-zags of the boundaries, default True),
    crease_angle (degrees; straightening never trades a crease edge for a smoother one),
    crease_line_angle (degrees; chains of edges this sharp join the feature lines; 0, the
    default: only the cluster boundaries), seam_lines (texture seams the preparation marked
    join the feature lines, default True), skin_lines (on a skinned mesh, the boundaries between
    the faces different joints dominate join the feature lines, default False).
    """
    f = _run_on(TriChartFeatures.tcFeatureRefinement(), clusters, "features", progress, options)
    return _output(f, 0), _output(f, 1), _output(f, 2)


def base_complex(features, progress=None, **options):
    """tcBaseComplex on a closed manifold mesh (normally refine_features' output); returns
    (base complex, input mesh with BaseFaceId and BaseBarycentric).

    Options: target_faces, max_error.
    """
    f = _run_on(TriChartBaseComplex.tcBaseComplex(), features, "base", progress, options)
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


def multilevel_mesh(mesh, progress=None, **options):
    """tcMultilevelMesh on a triangle mesh; returns the multiblock of its levels (Kircher and
    Garland 2005), finest first: block k the mesh of level k with point arrays ParentId,
    ClusterSize and QuadricError, block 0 the input with ClusterId1 .. ClusterIdn too.

    Options: branching_factor (default 8), max_levels (0: no limit), coarsest_vertices,
    link_condition (default True: level 1 homeomorphic to the input).
    """
    f = _run_on(TriChartMultilevel.tcMultilevelMesh(), mesh, "multilevel", progress, options)
    return _multiblock(f)


def geometry_images(patches, resampled_arrays=(), progress=None, **options):
    """tcGeometryImages on trace_paths' first output; returns the atlas (a multiblock of the
    chart table and one image per mip step).

    Options: error_target (fraction of the diagonal that every chart's measured error is
    brought below; default 7e-4; 0: none, the budget alone), sample_budget, min_level, max_level,
    curvature_weight, level_rule (0: by curvature-weighted area, 1: by measured error, the
    default), stretch_iterations
    (stretch-reducing passes over each mean-value map, default 10; 0: Floater's map alone),
    keep_appearance (default True: resample TextureCoordinates and Colors when the mesh has
    them and carry its base-colour texture into the atlas).
    """
    f = TriChartGeometryImages.tcGeometryImages()
    for name in resampled_arrays:
        f.AddResampledArray(name)
    return _multiblock(_run_on(f, patches, "images", progress, options))


def rebuild(atlas, level=None, chart_levels=None, progress=None):
    """tcGeometryImageMesh: the mesh of `atlas` with every chart at `level` (-1: its finest;
    None: the filter's default, its finest), or at chart_levels[c] for chart c, stitched
    without cracks."""
    f = TriChartGeometryImages.tcGeometryImageMesh()
    f.SetInputData(atlas)
    if level is not None:
        f.SetLevel(level)
    if chart_levels is not None:
        from vtkmodules.vtkCommonCore import vtkIntArray

        levels = vtkIntArray()
        for value in chart_levels:
            levels.InsertNextValue(int(value))
        f.SetChartLevels(levels)
    run(f, "rebuild", progress)
    return _output(f)


def simplify_qem(mesh, target_triangles, progress=None):
    """tcMeshoptSimplify: meshoptimizer's QEM simplification of a triangle mesh to at most
    target_triangles triangles (the input's triangles for a target at or above its count)."""
    f = TriChartGeometryImages.tcMeshoptSimplify()
    f.SetTargetTriangles(int(target_triangles))
    return _output(_run_on(f, mesh, "simplify", progress, {}))


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


def check_atlas_file_name(path):
    """Raise TriChartError unless `path` names an atlas file (.exr)."""
    if not TriChartIO.tcAtlasWriter.IsAtlasFileName(str(path)):
        raise TriChartError(f"cannot write the atlas '{path}': an atlas file is OpenEXR, named "
                            f".exr (a mesh for other tools: trichart mesh; an LOD chain: "
                            f"trichart export)")


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


# The mesh formats TriChart writes, by extension: tcMeshWriter's.
MESH_EXTENSIONS = tuple(TriChartIO.tcMeshWriter.GetSupportedExtensions().split())


def check_mesh_file_name(path):
    """Raise TriChartError unless `path` names a mesh format TriChart writes."""
    if not TriChartIO.tcMeshWriter.IsMeshFileName(str(path)):
        extension = os.path.splitext(str(path))[1].lower()
        raise TriChartError(
            f"cannot write '{path}': unknown extension '{extension}'; a mesh is written as "
            f"{', '.join(MESH_EXTENSIONS)} (an atlas as .exr: trichart build; an LOD chain as "
            f".glb or .gltf: trichart export)")
    return os.path.splitext(str(path))[1].lower()


def write_mesh(mesh, path):
    """Write `mesh` with tcMeshWriter in the format its extension names (MESH_EXTENSIONS;
    anything else, or polygons for STL and OFF, is refused with TriChartError); the file
    appears only when complete (temporary file, then rename)."""
    check_mesh_file_name(path)
    path = os.path.abspath(str(path))
    writer = TriChartIO.tcMeshWriter()
    writer.SetFileName(path)
    writer.SetInputData(mesh)
    run(writer, "write")
    if writer.GetErrorCode() != 0:
        raise TriChartError(f"cannot write '{path}' (disk full or not writable?)")
    return path


def base_color_texture(mesh):
    """The base-colour texture `mesh` carries (the field arrays tcMeshReader and tcGeometryImageMesh
    give it) as a vtkTexture, linear, mipmapped and repeated as glTF samples it; None without
    one. Draw it with the mesh's TextureCoordinates as its active texture coordinates."""
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkRenderingCore import vtkTexture

    fd = mesh.GetFieldData()
    rgba = fd.GetArray(TriChartIO.tcArrayNames.BaseColorTexture())
    size = fd.GetArray(TriChartIO.tcArrayNames.BaseColorTextureSize())
    if rgba is None or size is None:
        return None
    image = vtkImageData()
    image.SetDimensions(int(size.GetComponent(0, 0)), int(size.GetComponent(0, 1)), 1)
    image.GetPointData().SetScalars(rgba)
    texture = vtkTexture()
    texture.SetInputData(image)
    texture.InterpolateOn()
    texture.MipmapOn()
    texture.RepeatOn()
    return texture


def check_gltf_file_name(path):
    """Raise TriChartError unless `path` names a glTF file (.glb or .gltf)."""
    if not TriChartIO.tcGLTFWriter.IsGLTFFileName(str(path)):
        raise TriChartError(f"cannot write '{path}': a glTF file is named .glb (binary) or "
                            f".gltf (JSON)")


def export_gltf(atlas, path, progress=None, **options):
    """tcGLTFWriter: the atlas as a glTF 2.0 LOD chain in `path` (.glb or .gltf). Options:
    chain (0: by error, the default; 1: uniform levels), layout (0: MSFT_lod, the default; 1:
    named nodes), error_ratio, max_lods, error_pixels, viewport_height. Returns one dict per LOD
    written (triangles, error in input units, error_fraction of the diagonal, screen_coverage).
    """
    check_gltf_file_name(path)
    writer = TriChartIO.tcGLTFWriter()
    writer.SetFileName(str(path))
    writer.SetInputData(atlas)
    _configure(writer, options)
    run(writer, "export", progress)
    if writer.GetErrorCode() != 0 or writer.GetNumberOfLods() == 0:
        raise TriChartError(f"cannot write glTF '{path}'")
    diagonal = writer.GetInputDiagonal() or 1.0
    return [{"triangles": writer.GetLodTriangles(k), "error": writer.GetLodError(k),
             "error_fraction": writer.GetLodError(k) / diagonal,
             "screen_coverage": writer.GetLodScreenCoverage(k)}
            for k in range(writer.GetNumberOfLods())]


class _Stopwatch:
    """Runs stage functions, recording the seconds of each by name (a stage run again keeps its
    place in `seconds`)."""

    def __init__(self):
        self.seconds = {}

    def __call__(self, name, function, *args, **kwargs):
        start = time.perf_counter()
        value = function(*args, **kwargs)
        self.seconds[name] = time.perf_counter() - start
        return value


def _front(mesh, prepare_options, stage_options, progress, timed):
    """The stages from the preparation to the path tracing; returns (their outputs by name, in
    pipeline order, the preparation report)."""
    prepared = timed("prepare", _prepared, mesh, progress=progress, **prepare_options)
    # Fail here, not after curvature, clusters and features have run for minutes.
    _closed_manifold_check(prepared)
    clean, report = _output(prepared), prepared.GetReport()
    surface, crest = timed("curvature", curvature, clean, progress=progress,
                           **stage_options["curvature"])
    clustered, boundaries = timed("clusters", cluster, surface, progress=progress,
                                  **stage_options["cluster"])
    features, lines, corners = timed("features", refine_features, clustered,
                                     progress=progress, **stage_options["feature"])
    base, parameterized = timed("base", base_complex, features, progress=progress,
                                **stage_options["base"])
    patches, paths = timed("paths", trace_paths, parameterized, progress=progress)
    outputs = {"prepared": clean, "curvature": surface, "crest_lines": crest,
               "clusters": clustered, "cluster_boundaries": boundaries, "features": features,
               "feature_lines": lines, "corners": corners, "base_complex": base,
               "parameterized": parameterized, "patches": patches, "paths": paths}
    return outputs, report


def _front_retrying_slivers(mesh, prepare_options, stage_options, progress, timed,
                            retry_slivers):
    """_front; when the paths cannot be traced and the preparation kept the slivers, again with
    remove_slivers=True. Returns (outputs, report, what was retried or None)."""
    options = dict(prepare_options or {})
    try:
        return _front(mesh, options, stage_options, progress, timed) + (None,)
    except UntraceableError as error:
        if not retry_slivers or options.get("remove_slivers"):
            raise
        retried = (f"the paths could not be traced ({error.reason}); built again "
                   "with the slivers removed (--remove-slivers)")
        options["remove_slivers"] = True
        return _front(mesh, options, stage_options, progress, timed) + (retried,)


def _write_stages(folder, outputs, image):
    """Every output as `folder`/name.vtp (the folder exists) and, with `image`, pictures of curvature, features and
    the base complex; returns the written paths by name."""
    files = {name: write_mesh(data, os.path.join(folder, f"{name}.vtp"))
             for name, data in outputs.items()}
    if image:
        from .render import render_base_complex, render_curvature, render_features

        files["curvature_image"] = render_curvature(
            outputs["curvature"], outputs["crest_lines"], os.path.join(folder, "curvature.png"))
        files["features_image"] = render_features(
            outputs["features"], outputs["feature_lines"], outputs["corners"],
            os.path.join(folder, "features.png"))
        files["base_complex_image"] = render_base_complex(
            outputs["base_complex"], outputs["parameterized"],
            os.path.join(folder, "base_complex.png"))
    return files


def _read_within(path, progress, timed, max_memory, options, read_options):
    """read_mesh(path), refused (ResourceError) before the read when the counts the file
    declares already need more than max_memory, and after it for those read; returns (the
    mesh, the estimate of its build)."""
    counts = [-1, -1]
    TriChartIO.tcResources.GetMeshFileCounts(str(path), counts)
    if counts[1] >= 0:
        points = counts[0] if counts[0] >= 0 else counts[1] // 2
        _check_memory(points, counts[1], max_memory, f"'{path}' declares",
                      options)
    mesh = timed("read", read_mesh, path, progress, **read_options)
    polys = mesh.GetPolys()
    triangles = polys.GetNumberOfConnectivityIds() - 2 * polys.GetNumberOfCells()
    estimate = _check_memory(mesh.GetNumberOfPoints(), triangles, max_memory,
                             f"'{path}' has", options)
    return mesh, estimate


def build(path, atlas_path, stages=None, progress=None, image=True, curvature_options=None,
          cluster_options=None, feature_options=None, base_options=None,
          geometry_options=None, prepare_options=None, retry_slivers=True, max_memory=None,
          read_options=None):
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

    read_options are read_mesh's keyword options (vertical_scale for a terrain raster).

    Before the work starts (from the counts the file declares, then again from those read) the
    peak memory is estimated (estimate_memory); ResourceError refuses a build whose estimate
    exceeds max_memory bytes (None: the available memory; 0: no limit). The result's "memory"
    holds the estimate and the bytes the process held at the start.
    """
    check_atlas_file_name(atlas_path)
    timed = _Stopwatch()
    start = resident_memory()
    reset_peak_memory()
    mesh, estimate = _read_within(path, progress, timed, max_memory,
                                  (geometry_options, base_options, cluster_options),
                                  read_options or {})
    stage_options = {"curvature": curvature_options or {}, "cluster": cluster_options or {},
                     "feature": feature_options or {}, "base": base_options or {}}
    outputs, report, retried = _front_retrying_slivers(mesh, prepare_options, stage_options,
                                                       progress, timed, retry_slivers)
    atlas = timed("images", geometry_images, outputs["patches"], progress=progress,
                  **(geometry_options or {}))
    os.makedirs(os.path.dirname(os.path.abspath(str(atlas_path))), exist_ok=True)
    files = {"atlas": timed("write", write_atlas, atlas, atlas_path, progress)}
    if stages:
        os.makedirs(stages, exist_ok=True)
        outputs["rebuilt"] = rebuild(atlas, progress=progress)
        files.update(_write_stages(stages, outputs, image))
    return dict(outputs, atlas=atlas, files=files, report=report, mesh=outputs["prepared"],
                surface=outputs["curvature"], seconds=timed.seconds, retried=retried,
                memory={"estimate": estimate, "start": start})
