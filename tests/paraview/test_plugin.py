"""pvpython: the TriChart plugin loads, every proxy exists with its documented properties,
and reader -> preparation -> curvature runs with the expected arrays and counts."""
import os
import sys
import tempfile

from paraview import servermanager
from paraview.simple import LoadPlugin, OutputPort, UpdatePipeline

plugin = os.environ["TRICHART_PLUGIN"]
data = os.environ["TRICHART_TESTING_DATA"]
from pvcheck import check, failures  # noqa: E402  (beside this script)


LoadPlugin(plugin, remote=False, ns=globals())
from trichart import tcArrayNames  # noqa: E402  (the array names, from the wrapped modules)
# paraview.simple names the functions after the proxies' labels.
for name in ("TriChartMeshReader", "TriChartMeshPreparation", "TriChartCurvature",
             "TriChartSpectralClustering", "TriChartFeatureRefinement", "TriChartBaseComplex",
             "TriChartPathTracing", "TriChartGeometryImages", "TriChartGeometryImageMesh",
             "TriChartSurfaceDistance", "TriChartAtlasReader", "TriChartHeightFieldReader",
             "TriChartDeformationClustering", "TriChartMultilevelMesh"):
    check(name in globals(), f"proxy {name} is created by the plugin")
if failures:
    sys.exit(1)

reader = TriChartMeshReader(FileName=os.path.join(data, "meshes", "fandisk.off"))  # noqa: F821
prep = TriChartMeshPreparation(Input=reader)  # noqa: F821
check(prep.GetXMLName() == "tcMeshPreparation", "proxy name is the class name")
check(prep.MergeTolerance == 0.0 and prep.Orient == 1 and prep.SplitNonManifold == 0
      and prep.FillHoles == 0 and prep.MaxHoleEdges == 1000 and prep.RemoveSlivers == 0
      and prep.SliverAngle == 170.0 and prep.SliverEdgeRatio == 10.0
      and prep.DropNonOrientable == 0 and prep.MinComponentTriangles == 0
      and prep.KeepLargestComponent == 0,
      "tcMeshPreparation defaults match the C++ defaults")
curv = TriChartCurvature(Input=prep)  # noqa: F821
check(curv.MinNeighbors == 20 and curv.Degree == 3 and curv.ComputeCrestLines == 1,
      "tcCurvature defaults match the C++ defaults")
UpdatePipeline(proxy=curv)
surface = servermanager.Fetch(curv)
check(surface.GetNumberOfPoints() == 6475, "fandisk has 6475 points after preparation")
check(surface.GetNumberOfPolys() == 12946, "fandisk has 12946 triangles after preparation")
for array in (tcArrayNames.PrincipalCurvatures(), tcArrayNames.PrincipalDirections(),
              tcArrayNames.MeanCurvature(), tcArrayNames.GaussianCurvature()):
    check(surface.GetPointData().GetArray(array) is not None, f"point array {array}")
check(surface.GetCellData().GetArray(tcArrayNames.FaceMeanCurvature()) is not None,
      "cell FaceMeanCurvature")
info = curv.GetDataInformation(1)
check(info.GetNumberOfCells() > 0, "crest lines on output port 1")

curv.Degree = 2
UpdatePipeline(proxy=curv)
check(curv.GetDataInformation(0).GetNumberOfPoints() == 6475, "re-runs with a new property")

clusters = TriChartSpectralClustering(Input=curv, NumberOfClusters=12)  # noqa: F821
check(clusters.Seed == 1 and clusters.NystromThreshold == 100000 and clusters.NystromSamples == 500,
      "clustering defaults match the C++ defaults")
features = TriChartFeatureRefinement(Input=clusters)  # noqa: F821
check(features.BandFraction == 0.1 and features.CornerRings == 8
      and features.StraightenLines == 1 and features.CreaseAngle == 30.0, "refinement defaults")
UpdatePipeline(proxy=features)
clustered = servermanager.Fetch(clusters)
check(clustered.GetCellData().GetArray(tcArrayNames.ClusterId()).GetRange() == (0.0, 11.0),
      "12 clusters")
check(features.GetDataInformation(1).GetNumberOfCells() > 0, "feature lines on port 1")
check(features.GetDataInformation(2).GetNumberOfPoints() > 0, "corners on port 2")

base = TriChartBaseComplex(Input=features)  # noqa: F821
check(base.TargetFaces == 100 and base.MaxError == 1e-4, "base complex defaults")
UpdatePipeline(proxy=base)
check(0 < base.GetDataInformation(0).GetNumberOfCells() < 12946, "a coarse base complex")
check(base.GetDataInformation(1).GetNumberOfPoints() == 6475, "every input vertex parameterized")

paths = TriChartPathTracing(Input=OutputPort(base, 1))  # noqa: F821
images = TriChartGeometryImages(Input=paths)  # noqa: F821
check(images.MinLevel == 2 and images.MaxLevel == 8 and images.SampleBudget == 0
      and images.CurvatureWeight == 1.0 and images.LevelRule == "Error"
      and images.StretchIterations == 10 and images.FitSamples == 1,
      "geometry image defaults match the C++ defaults")
rebuilt = TriChartGeometryImageMesh(Input=images, Level=2)  # noqa: F821
check(TriChartGeometryImageMesh(Input=images).Level == -1, "rebuild default level")  # noqa: F821
distance = TriChartSurfaceDistance(Input=rebuilt, Reference=prep)  # noqa: F821
UpdatePipeline(proxy=distance)
patches = servermanager.Fetch(paths)
check(patches.GetCellData().GetArray(tcArrayNames.PatchId()) is not None, "patches carry PatchId")
check(paths.GetDataInformation(1).GetNumberOfCells() ==
      3 * base.GetDataInformation(0).GetNumberOfCells() // 2, "one path per base edge")
mesh = servermanager.Fetch(distance)
check(mesh.GetNumberOfPolys() > 0
      and mesh.GetCellData().GetArray(tcArrayNames.ChartId()) is not None,
      "a mesh rebuilt from the atlas, with ChartId")
check(mesh.GetPointData().GetArray(tcArrayNames.Distance()) is not None, "point array Distance")
hausdorff = mesh.GetFieldData().GetArray(tcArrayNames.RelativeHausdorff())
check(hausdorff is not None and 0 < hausdorff.GetValue(0) < 0.05,
      "level 2 of fandisk is within 5% of the diagonal")

# A terrain raster through the height-field proxy of the same reader, its heights scaled.
grid = os.path.join(tempfile.mkdtemp(), "ridge.asc")
with open(grid, "w") as f:
    f.write("ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 5\n1 4 2\n3 5 1\n")
terrain = TriChartHeightFieldReader(FileName=grid, VerticalScale=2.0)  # noqa: F821
UpdatePipeline(proxy=terrain)
info = terrain.GetDataInformation(0)
check(info.GetNumberOfPoints() == 6 and info.GetNumberOfCells() == 4,
      "a 3 x 2 height field is 6 points and 4 triangles")
check(tuple(info.GetBounds()[4:]) == (2.0, 10.0), "heights times VerticalScale")
elevation = info.GetPointDataInformation().GetArrayInformation(tcArrayNames.Elevation())
check(elevation is not None and tuple(elevation.GetComponentRange(0)) == (1.0, 5.0),
      "point array Elevation holds the heights read")

print("paraview plugin test:", "FAILED" if failures else "passed")
sys.exit(1 if failures else 0)
