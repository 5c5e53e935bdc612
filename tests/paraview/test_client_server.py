"""pvpython, client-server: a local pvserver (on a free port) builds the bundled bunny's atlas
and reads it back; the client shows it with the "TriChart LOD" representation and the picture
has the surface, rendered on the client (the server delivers the atlas) and on the server (it
sends the image). The plugin is loaded on both sides. The server is stopped in every case: it
runs under `timeout` (and under its own xvfb-run), in its own process group, which the test ends
in `finally` (and which gets SIGTERM if the test dies); the test checks that no process is left."""
import ctypes
import os
import select
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

from paraview.simple import (Connect, Delete, Disconnect, GetSources, LoadPlugin,
                             Render, ResetCamera, SaveScreenshot, Show, UpdatePipeline)

plugin = os.environ["TRICHART_PLUGIN"]
pvserver = os.environ.get("TRICHART_PVSERVER", "pvserver")
data = os.environ["TRICHART_TESTING_DATA"]
from pvcheck import black_view, build_atlas, check, failures, lit_pixels  # noqa: E402  (beside this script)

# The server may live at most this long (coreutils timeout kills it), within ctest's TIMEOUT.
SERVER_SECONDS = 150
STARTUP_SECONDS = 60


def free_port():
    """A TCP port nobody listens on now (the kernel's choice)."""
    with socket.socket() as probe:
        probe.bind(("localhost", 0))
        return probe.getsockname()[1]


def wait_for_listening(server, seconds):
    """Reads the server's output until it accepts connections; returns what it printed, or
    None when it exits or stays silent for `seconds`. (os.read, not readline: a buffered
    reader would hold lines that select no longer sees.)"""
    printed = b""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        ready, _, _ = select.select([server.stdout], [], [], 1.0)
        if not ready:
            if server.poll() is not None:
                return None
            continue
        chunk = os.read(server.stdout.fileno(), 4096)
        if not chunk:
            return None
        printed += chunk
        if b"Accepting connection" in printed:
            return printed.decode(errors="replace").split("\n")
    return None


def stop(server):
    """Ends the server's process group, whatever state it is in: SIGTERM, then SIGKILL. (In
    ParaView 5.11 pvpython's Disconnect does not close the socket while the interpreter lives,
    so the server does not exit on its own.)"""
    for sig in (signal.SIGTERM, signal.SIGKILL):
        try:
            os.killpg(server.pid, sig)
        except ProcessLookupError:
            break
        try:
            server.wait(timeout=10)
            break
        except subprocess.TimeoutExpired:
            continue
    rest = server.stdout.read().decode(errors="replace")
    server.stdout.close()
    # What the server said after it listened (its errors, if any), without the stack traces.
    said = [line for line in rest.splitlines()
            if line.strip() and not line.strip().split(" ", 1)[0].isdigit()]
    print("pvserver said:", "\n  ".join(said[-20:]) if said else "nothing more")


def end_with_parent():
    """In the server's first process: SIGTERM when this test dies (ctest's TIMEOUT), so that
    the server's group goes with it rather than at SERVER_SECONDS."""
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG


def server_processes(port):
    """The processes whose command line names the server's port (pvserver, its timeout)."""
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/cmdline", "rb") as f:
                arguments = f.read().split(b"\0")
        except OSError:
            continue
        if f"--server-port={port}".encode() in arguments:
            found.append(int(entry))
    return found


def group_members(pgid):
    """The live processes of process group `pgid` (zombies left to init are not)."""
    found = []
    for entry in os.listdir("/proc"):
        try:
            with open(f"/proc/{entry}/stat") as f:
                # pid (command) state ppid pgrp ...: the command may hold spaces, not ")".
                fields = f.read().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        if fields[0] != "Z" and int(fields[2]) == pgid:
            found.append(int(entry))
    return found


def picture(view, name, folder):
    """Renders `view` to a PNG; (lit pixels, all pixels)."""
    Render(view)
    path = os.path.join(folder, name)
    SaveScreenshot(path, view, ImageResolution=[400, 400], TransparentBackground=0)
    return lit_pixels(path)


def session(port, folder):
    """Everything done while connected."""
    connection = Connect("localhost", port)
    check(connection is not None and connection.IsRemote(), "the client connects to pvserver")
    if connection is None:
        return
    LoadPlugin(plugin, remote=True, ns=globals())
    LoadPlugin(plugin, remote=False, ns=globals())
    import trichart.TriChartParaView  # noqa: F401  (the representation's Python class)

    atlas_file = os.path.join(folder, "bunny.exr")
    build_atlas(globals(), os.path.join(data, "meshes", "bunny_npm.off"), atlas_file)
    atlas = TriChartAtlasReader(FileName=atlas_file)  # noqa: F821
    UpdatePipeline(proxy=atlas)
    charts = atlas.GetDataInformation().DataInformation.GetNumberOfRows()
    print("charts in the atlas (on the server):", charts)
    check(charts > 0, "the server reads the atlas back")

    view = black_view()
    display = Show(atlas, view)
    display.Representation = "TriChart LOD"
    display.DiffuseColor = [1.0, 0.8, 0.2]
    ResetCamera(view)
    # The client's own representation: it has no input, only what the server delivers.
    client = display.GetClientSideObject().GetActiveRepresentation()

    results = {}
    for mode, threshold in (("client", 1.0e6), ("server", 0.0)):
        view.RemoteRenderThreshold = threshold  # MB of geometry above which the server renders
        lit, total = picture(view, f"{mode}.png", folder)
        drawn = client.GetChartsDrawn()
        results[mode] = lit
        print(f"rendered on the {mode}: {lit} of {total} pixels lit; the client's mapper drew "
              f"{drawn} charts")
        check(0.05 * total < lit < 0.6 * total, f"the bunny covers part of the {mode}'s picture")
        check(not client.GetInputIsAtlas(), "the client's representation has no input of its own")
        if mode == "client":
            check(drawn == charts, "the client draws every chart the server delivered")
            # The client converts the delivered atlas once: a second frame draws the same one.
            converted = client.GetMapper().GetInputDataObject(0, 0)
            Render(view)
            again = client.GetMapper().GetInputDataObject(0, 0)
            check(converted is not None and again is not None
                  and converted.GetAddressAsString("vtkObject") == again.GetAddressAsString(
                      "vtkObject") and converted.GetMTime() == again.GetMTime(),
                  "the client's mapper keeps the atlas it converted from one frame to the next")
        else:
            check(drawn == 0, "with remote rendering the client draws nothing itself")
    check(abs(results["client"] - results["server"]) <= 0.02 * results["client"],
          "the client and the server draw the same picture")
    del client, display, atlas
    Delete(view)
    del view
    # Every pipeline proxy, so that nothing keeps the session (and its socket) open.
    for proxy in list(GetSources().values()):
        Delete(proxy)
    del connection


def connected_session(port, folder):
    """session() in a connection that is closed whatever happens."""
    try:
        session(port, folder)
    finally:
        Disconnect()


def main():
    folder = tempfile.mkdtemp(prefix="trichart-pv-cs-")
    port = free_port()
    # --foreground: timeout stays in the server's process group, which stop() ends.
    command = ["timeout", "--foreground", "--kill-after=5", str(SERVER_SECONDS), pvserver,
               "--force-offscreen-rendering", f"--server-port={port}"]
    if shutil.which("xvfb-run"):
        # A display of its own, so that the server's windows never wait on the client's; -noreset
        # as in scripts/test.sh (a window that connects while Xvfb resets fails).
        command = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24 -noreset"] + command
    server = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              start_new_session=True, preexec_fn=end_with_parent)
    try:
        printed = wait_for_listening(server, STARTUP_SECONDS)
        check(printed is not None, f"pvserver listens on port {port} within {STARTUP_SECONDS} s")
        if printed is not None:
            print("pvserver:", " | ".join(line.strip() for line in printed if line.strip()))
            connected_session(port, folder)
    finally:
        stop(server)
        print("pvserver exit status:", server.returncode)
        left = sorted(set(group_members(server.pid) + server_processes(port)))
        check(not left,
              f"no server process is left behind (left: {left})")
        shutil.rmtree(folder, ignore_errors=True)
    print("TriChart client-server test:", "FAILED" if failures else "passed")
    return 1 if failures else 0


sys.exit(main())
