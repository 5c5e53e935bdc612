"""pvpython: the "TriChart LOD" representation holds one converted copy of the atlas. Its
update converts the atlas once, in the mapper that draws it, and the renders that follow (after
a change of a display property, or of the input) convert nothing more. Measured with glibc's
heap statistics (mallinfo2): the bytes in use that the representation's update adds (one copy),
and those that the renders after a new input add (far less than a copy).

pvpython test_lod_memory.py [ATLAS.exr]: with an atlas file, measures that one instead of
building the bundled bunny's (the figures are printed either way)."""
import ctypes
import os
import shutil
import sys
import tempfile

libc = ctypes.CDLL("libc.so.6")

from paraview.simple import CreateView, Delete, LoadPlugin, Render, ResetCamera, Show  # noqa: E402

plugin = os.environ["TRICHART_PLUGIN"]
data = os.environ["TRICHART_TESTING_DATA"]
from pvcheck import build_atlas, check, failures  # noqa: E402  (beside this script)


class MallInfo2(ctypes.Structure):
    _fields_ = [(name, ctypes.c_size_t) for name in (
        "arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks", "fsmblks", "uordblks",
        "fordblks", "keepcost")]


if not hasattr(libc, "mallinfo2"):
    print("FAILED: this C library has no mallinfo2 (glibc 2.33 or later measures the heap)")
    sys.exit(1)
libc.mallinfo2.restype = MallInfo2
MiB = float(1 << 20)


def in_use():
    """Bytes the process has allocated and not freed (heap and mapped blocks)."""
    info = libc.mallinfo2()
    return info.uordblks + info.hblkhd


LoadPlugin(plugin, remote=False, ns=globals())
import trichart.TriChartParaView  # noqa: E402,F401  (the representation's Python class)

folder = tempfile.mkdtemp(prefix="trichart-pv-memory-")
if len(sys.argv) > 1:
    atlas_files = [sys.argv[1], os.path.join(folder, "copy.exr")]
    shutil.copyfile(sys.argv[1], atlas_files[1])
else:
    # 500,000 samples, all spent (the budget rule, no error target): one converted copy is a
    # few MiB, far above the noise.
    atlas_files = [os.path.join(folder, "bunny.exr"), os.path.join(folder, "copy.exr")]
    build_atlas(globals(), os.path.join(data, "meshes", "bunny_npm.off"), atlas_files[0],
                SampleBudget=500000, ErrorTarget=0.0)
    shutil.copyfile(atlas_files[0], atlas_files[1])

atlas = TriChartAtlasReader(FileName=atlas_files[0])  # noqa: F821
atlas.UpdatePipeline()
read = atlas.GetClientSideObject().GetOutputDataObject(0)
charts = read.GetBlock(0).GetNumberOfRows()
# The converted atlas (tc::Atlas) holds the images' samples as float32, as the reader's images
# do: one copy is about the size of the images block.
copy = read.GetBlock(1).GetActualMemorySize() * 1024
print(f"atlas: {charts} charts, images {copy / MiB:.1f} MiB")

view = CreateView("RenderView")
view.ViewSize = [400, 400]
display = Show(atlas, view)
display.Representation = "TriChart LOD"
lod = display.GetClientSideObject().GetActiveRepresentation()
executions = []
lod.AddObserver("StartEvent", lambda *_: executions.append(1))
mapper = lod.GetMapper()
errors = []
mapper.AddObserver("ErrorEvent", lambda *_: errors.append(1))

before = in_use()
view.Update()
held = in_use() - before
print(f"first update: holds {held / MiB:.1f} MiB more; the mapper has "
      f"{mapper.GetNumberOfCharts()} charts")
check(mapper.GetNumberOfCharts() == charts, "the update converted the atlas in the drawing mapper")
check(0.8 * copy < held < 1.5 * copy,
      "the update keeps one converted copy of the atlas (not none, not two)")

# The first render also creates the graphics buffers (which Mesa allocates with malloc), so it is
# measured for the figures only; the renders after a new input below show that none converts.
before = in_use()
ResetCamera(view)
Render(view)
rendered = in_use() - before
print(f"first ResetCamera and render: hold {rendered / MiB:+.1f} MiB; charts drawn "
      f"{lod.GetChartsDrawn()}")
check(lod.GetChartsDrawn() == charts, "the first render draws every chart")

display.LODBias = 1.0
before = in_use()
Render(view)
print(f"LODBias 1: executions {len(executions)}, the render holds "
      f"{(in_use() - before) / MiB:+.1f} MiB")
check(len(executions) == 1, "a display property does not re-execute the representation")
check(abs(in_use() - before) < 0.25 * copy, "a display property does not convert the atlas")

# A new input (the reader re-reads): converted once, in the update, replacing the old copy.
for number, name in enumerate((atlas_files[1], atlas_files[0], atlas_files[1]), start=2):
    atlas.FileName = name
    before = in_use()
    view.Update()
    updated = in_use() - before
    before = in_use()
    Render(view)
    rendered = in_use() - before
    print(f"new input: the update holds {updated / MiB:+.1f} MiB, the render "
          f"{rendered / MiB:+.1f} MiB; charts drawn {lod.GetChartsDrawn()}")
    check(len(executions) == number, "a new input re-executes the representation")
    check(abs(updated) < 0.2 * copy, "the update of a new input replaces the converted copy")
    check(abs(rendered) < 0.25 * copy, "the render after a new input does not convert it again")
    check(lod.GetChartsDrawn() == charts, "the new input is drawn")
check(not errors, "the mapper reports no error")

print("TriChart LOD memory test:", "FAILED" if failures else "passed")
del lod, mapper
Delete(view)
del view
shutil.rmtree(folder)
sys.exit(1 if failures else 0)
