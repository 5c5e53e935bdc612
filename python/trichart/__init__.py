"""TriChart: feature-preserving triangle-chart geometry images and level of detail for VTK.

The filters are VTK algorithms (tcMeshReader, tcMeshPreparation, tcCurvature, ...); the
helpers in :mod:`trichart.pipeline` chain them, :mod:`trichart.render` draws a stage, and
``python3 -m trichart`` (the ``trichart`` command) runs them from the shell. The names of the
arrays the stages write are those of the C++ filters, read from ``tcArrayNames``
(``trichart.tcArrayNames.MeanCurvature()``), never retyped.
"""
import os as _os

# The wrapped modules link to the same VTK libraries as vtkmodules; import it first.
import vtkmodules.vtkCommonCore  # noqa: F401
import vtkmodules.vtkCommonExecutionModel  # noqa: F401

from .TriChartIO import *  # noqa: F401,F403
from .TriChartPreparation import *  # noqa: F401,F403
from .TriChartCurvature import *  # noqa: F401,F403
from .TriChartFeatures import *  # noqa: F401,F403
from .TriChartBaseComplex import *  # noqa: F401,F403
from .TriChartGeometryImages import *  # noqa: F401,F403
from .TriChartSkinning import *  # noqa: F401,F403
from .TriChartMultilevel import *  # noqa: F401,F403
import vtkmodules.vtkRenderingCore  # noqa: E402,F401  (before the mapper's module, as above)
import vtkmodules.vtkRenderingOpenGL2  # noqa: E402,F401
from .TriChartRendering import *  # noqa: E402,F401,F403

try:
    from . import _config_build as _config  # running from a build tree
except ImportError:
    from . import _config

__version__ = _config.VERSION

from .pipeline import (read_mesh, prepare, curvature, cluster, refine_features,  # noqa: E402,F401
                       base_complex, trace_paths, geometry_images, rebuild, surface_distance,
                       read_atlas, write_atlas, atlas_charts, build, TriChartError,
                       UntraceableError, ResourceError, estimate_memory, set_max_threads,
                       write_mesh, export_gltf, simplify_qem, MESH_EXTENSIONS,
                       base_color_texture, read_skeleton, read_frames, time_steps, animation_names,
                       pose, deformation_clustering, multilevel_mesh)


def plugin_path():
    """Path of the ParaView plugin that matches this package ('' when it was not built)."""
    return _config.PLUGIN_PATH if _os.path.exists(_config.PLUGIN_PATH) else ""
