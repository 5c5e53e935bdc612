"""pvpython: a skinned scene read by the TriChart reader plays in ParaView: its time steps
reach the animation scene, each time gives the mesh posed at that time, and the skeleton is
the reader's second output."""
import os
import sys

from paraview import servermanager
from paraview.simple import GetAnimationScene, LoadPlugin, UpdatePipeline

plugin = os.environ["TRICHART_PLUGIN"]
shared = os.environ.get("TRICHART_SHARED_DATA", "")
from pvcheck import check, failures  # noqa: E402  (beside this script)

snake = os.path.join(shared, "skinned", "snake_fbx", "animation_with_skeleton.fbx")
if not os.path.isfile(snake):
    print(f"skipped: {snake} is absent (../shared/data not beside the checkout)")
    sys.exit(0)

LoadPlugin(plugin, remote=False, ns=globals())
reader = TriChartMeshReader(FileName=snake)  # noqa: F821
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues)
check(len(times) == 14 and times[0] == 0.0 and abs(times[-1] - 20 / 24) < 1e-9,
      f"14 key times from 0 to 0.8333 s (got {len(times)})")
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
check(abs(scene.EndTime - times[-1]) < 1e-9, "the animation scene spans the animation")

bounds = []
for t in (0.0, 0.5):
    UpdatePipeline(time=t, proxy=reader)
    bounds.append(reader.GetDataInformation(0).GetBounds())
check(bounds[0] != bounds[1], f"the mesh moves between 0 and 0.5 s ({bounds})")
skeleton = servermanager.Fetch(reader, idx=1)
check(skeleton.GetNumberOfPoints() == 17 and skeleton.GetNumberOfLines() == 16,
      "the skeleton: 17 joints, a line to each parent")

reader.BindPose = 1
reader.UpdatePipelineInformation()
check(len(reader.TimestepValues) == 0, "BindPose announces no time steps")
sys.exit(1 if failures else 0)
