"""pvpython: an atlas written by TriChart Atlas Writer and read back by TriChart Atlas Reader is
shown with the "TriChart LOD" representation: its mapper draws every chart, the picture is not
empty, LODBias changes the triangles drawn, and data that is not an atlas is reported and not
drawn."""
import os
import shutil
import sys
import tempfile

from paraview import servermanager
from paraview.simple import (Delete, GroupDatasets, LoadPlugin, Render, ResetCamera,
                             SaveScreenshot, Show, Sphere, UpdatePipeline)
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING

plugin = os.environ["TRICHART_PLUGIN"]
data = os.environ["TRICHART_TESTING_DATA"]
from pvcheck import black_view, build_atlas, check, failures, lit_pixels  # noqa: E402  (beside this script)


LoadPlugin(plugin, remote=False, ns=globals())
# The representation's Python class, so that its client-side object shows its own methods.
import trichart.TriChartParaView  # noqa: E402,F401

# The static pipeline on the bundled bunny, to an atlas file and back.
folder = tempfile.mkdtemp(prefix="trichart-pv-")
atlas_file = os.path.join(folder, "bunny.exr")
build_atlas(globals(), os.path.join(data, "meshes", "bunny_npm.off"), atlas_file)
check(os.path.isfile(atlas_file), "TriChart Atlas Writer wrote the atlas")
atlas = TriChartAtlasReader(FileName=atlas_file)  # noqa: F821
UpdatePipeline(proxy=atlas)
charts = servermanager.Fetch(atlas).GetBlock(0).GetNumberOfRows()
print("charts in the atlas:", charts)
check(charts > 0, "the atlas read back has charts")

view = black_view()
display = Show(atlas, view)
print("default representation of an atlas:", display.GetXMLName())
check("TriChart LOD" in display.GetProperty("Representation").Available,
      "'TriChart LOD' is a representation type of the atlas")
display.Representation = "TriChart LOD"
display.DiffuseColor = [1.0, 0.8, 0.2]
ResetCamera(view)
Render(view)

# The builtin session's representation object: the composite's active one.
lod = display.GetClientSideObject().GetActiveRepresentation()
check(lod.GetClassName() == "tcLODRepresentation", "the client-side object is tcLODRepresentation")
check(lod.GetInputIsAtlas(), "the representation recognises the atlas")
drawn = lod.GetChartsDrawn()
triangles = lod.GetTrianglesDrawn()
print("LODBias 0: charts drawn", drawn, "triangles drawn", triangles)
check(drawn == charts, "every chart is drawn when the whole atlas is in view")
check(triangles > 0, "triangles are drawn")
check(display.LODBias == 0.0 and display.ErrorTarget == 1.0 and display.FreezeLOD == 0
      and display.LODColorMode == "Actor",
      "TriChart LOD defaults: the mapper's, with a 1-pixel error target as in the viewer")

screenshot = os.path.join(folder, "lod.png")
SaveScreenshot(screenshot, view, ImageResolution=[400, 400], TransparentBackground=0)
lit, total = lit_pixels(screenshot)
print("non-background pixels:", lit, "of", total)
check(0.02 * total < lit < 0.95 * total, "the atlas covers part of the picture")

display.LODBias = 2.0
Render(view)
finer = lod.GetTrianglesDrawn()
display.LODBias = -2.0
Render(view)
coarser = lod.GetTrianglesDrawn()
print("triangles drawn at LODBias -2, 0, 2:", coarser, triangles, finer)
check(coarser < triangles < finer, "LODBias changes the triangles drawn")
check(lod.GetChartsDrawn() == charts, "LODBias changes levels, not the charts drawn")

display.LODBias = 0.0
display.LODColorMode = "Chart"
display.LODWireframe = 1
Render(view)
check(lod.GetMapper().GetColorMode() == 1, "LODColorMode reaches the mapper")
check(lod.GetActor().GetProperty().GetRepresentation() == 1, "LODWireframe draws the grid edges")
check(lod.GetActor().GetProperty().GetDiffuseColor() == (1.0, 0.8, 0.2),
      "the solid colour is shared with the surface representation")

# A multiblock that is not an atlas: reported, with the way out, and nothing drawn.
messages = []


@calldata_type(VTK_STRING)
def collect(obj, event, message):
    messages.append(message)


group = GroupDatasets(Input=Sphere())
other = Show(group, view)
other.Representation = "TriChart LOD"
other_lod = other.GetClientSideObject().GetActiveRepresentation()
other_lod.AddObserver("ErrorEvent", collect)
Render(view)
print("not an atlas:", messages[0] if messages else "(no error)")
check(not other_lod.GetInputIsAtlas(), "a sphere is not an atlas")
check(other_lod.GetChartsDrawn() == 0, "nothing is drawn for a sphere")
check(any("TriChart Geometry Image Mesh" in m for m in messages),
      "the error tells the user to apply TriChart Geometry Image Mesh")

print("TriChart LOD representation test:", "FAILED" if failures else "passed")
# pvpython crashes in sys.exit while a render view is alive (ParaView 5.11, even with a
# sphere): release the view, and the references into it, first.
del lod, other_lod
Delete(view)
del view
shutil.rmtree(folder)
sys.exit(1 if failures else 0)
